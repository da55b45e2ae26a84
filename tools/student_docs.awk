# student_docs.awk: rewrites one page of docs/ for a student copy in which tasks are blanked, so that it
# gives no model answer away (the coursework kit; tools/student.sh runs it on every page of a hand-out).
#
#   awk -v copy=STAGE -v files="common/sphere.c ..." -v tasks="all" -f tools/student_docs.awk docs/*.md
#
# copy is the folder holding the copy's files as they will be (the blanked sources among them), where
# each page is written (STAGE/docs/02-sphere.md); files the code files a listing may quote (as
# tests/test_docs.c reads them); tasks the blanked tasks.
#
#  - A ```c listing that quotes a blanked function's body shows that function's stub instead, taken from
#    the copy, after a line saying whose task it is; a second listing of the same body says so in a line.
#    A listing found in the copy as it is stays; one of a static helper that the copy marks unused is
#    quoted with the mark, as the copy has it. So every listing is still the copy's code, word for word.
#  - A ★★ exercise that asks for a change in a blanked function of its chapter ("In `traverse`", "the body
#    of `clip_to_slab`"; another chapter's when it names the file too) gains a line saying that the
#    student makes it in their own function, once its task is done.
#  - The gallery page (docs/gallery.md) loses the diffs of its faults, and the paragraph on the patches
#    gets one on their absence: each is a wrong version of a task's body, and a hand-out has no patches.
#  - The lecturer's guide (docs/coursework.md) is not in a hand-out: a link to it keeps only its words, and
#    its entry in the list of pages (docs/README.md) goes.
function chosen(id) { return tasks == "all" || (tasks != "none" && index(" " tasks " ", " " id " ") > 0) }
function read_file(path,    line, text, status) {
    text = ""
    while ((status = (getline line < path)) > 0) text = text line "\n"
    close(path)
    return status < 0 ? "" : text
}
# The text of the function that follows the marker line `marker` in text: from the line after the marker
# to the first line that is "}" alone.
function function_after_marker(text, marker,    n, lines, k, body) {
    n = split(text, lines, "\n")
    for (k = 1; k <= n; k++)
        if (lines[k] == marker) break
    body = ""
    for (k++; k <= n; k++) {
        body = body lines[k] "\n"
        if (lines[k] == "}") return body
    }
    return ""
}
function function_name(text,    head) {
    gsub(/__attribute__\(\([^)]*\)\)/, "", text)
    head = substr(text, 1, index(text, "(") - 1)
    sub(/^.*[ *]/, "", head)
    return head
}
BEGIN {
    nfiles = split(files, file_list, " ")
    corpus = ""
    for (f = 1; f <= nfiles; f++) {
        path = file_list[f]
        reference[path] = read_file(path)
        copied[path] = read_file(copy "/" path)
        corpus = corpus copied[path] "\001"
        # The marked functions of this file: task, start and end offsets in the reference text.
        n = split(reference[path], lines, "\n")
        offset = 1
        for (k = 1; k <= n; k++) {
            if (match(lines[k], /^\/\* TASK [0-9]+\.[0-9]+( ALSO)?: .* \*\/$/)) {
                id = lines[k]; sub(/^\/\* TASK /, "", id); sub(/( ALSO)?:.*$/, "", id)
                start = offset
                end = offset + length(lines[k]) + 1
                for (j = k + 1; j <= n; j++) {
                    end += length(lines[j]) + 1
                    if (lines[j] == "}") break
                }
                spans++
                span_file[spans] = path; span_id[spans] = id; span_start[spans] = start; span_end[spans] = end
                span_marker[spans] = lines[k]
                name = function_name(lines[k + 1] lines[k + 2])
                span_name[spans] = name
                span_also[spans] = lines[k] ~ / ALSO: /
                task_of_name[name] = task_of_name[name] " " id
                name_file[name] = path
                if (!span_also[spans]) task_name[id] = name
            }
            offset += length(lines[k]) + 1
        }
    }
}
FNR == 1 && NR > 1 { rewrite(previous) }
FNR == 1 { page_lines = 0; previous = FILENAME }
{ page[++page_lines] = $0 }
END { if (NR > 0) rewrite(previous) }
# Prints a line of the page; a hand-out has no lecturer's guide, so a link to it keeps only its words.
function emit(text,    words) {
    gsub(/, see \[[^]]*\]\(coursework\.md[^)]*\)/, "", text) # "(make check-N, see [the kit](coursework.md))"
    while (match(text, /\[[^]]*\]\(coursework\.md[^)]*\)/)) {
        words = substr(text, RSTART + 1, RLENGTH); sub(/\]\(.*$/, "", words)
        text = substr(text, 1, RSTART - 1) words substr(text, RSTART + RLENGTH)
    }
    print text > out
}
# Writes the page just read (page[1..page_lines], from path) into the copy.
function rewrite(path,    name) {
    out = copy "/" path
    name = path; sub(/^.*\//, "", name)
    chapter = name ~ /^[0-9][0-9]-/ ? substr(name, 1, 2) + 0 : 0
    gallery = name == "gallery.md"
    split("", shown)
    for (i = 1; i <= page_lines; i++) {
        line = page[i]
        if (gallery && line == "```diff") {
            while (i < page_lines && page[++i] != "```") ;
            continue
        }
        if (gallery && index(line, "* **The change:** ") == 1) continue
        if (gallery && index(line, "The pictures are rendered by `make gallery`") == 1) {
            while (i < page_lines && page[i + 1] != "") i++
            emit("In this student copy the changes that make these pictures are left out: each is a wrong version of")
            emit("a function you write. The pictures, their symptoms and the checks that catch them (`make check-N`)")
            emit("stay, to help you recognise a mistake when your own picture shows one.")
            continue
        }
        if (line ~ /^\* \[[^]]*\]\(coursework\.md\)/) { # the list of pages: the guide is not in the copy
            while (i < page_lines && page[i + 1] ~ /^  /) i++
            continue
        }
        if (line == "```c") { listing(i); continue }
        if (line ~ /^[0-9]+\. ★★ /) { exercise(i); continue }
        emit(line)
    }
    close(out)
}
# Prints the ```c listing that starts at page line `at` as the copy needs it, and moves i past it.
function listing(at,    block, k, variant, lines, n, j, found, path, p, s, stubs, id, stub) {
    block = ""
    for (k = at + 1; k <= page_lines && page[k] != "```"; k++) block = block page[k] "\n"
    i = k
    if (index(corpus, block) > 0) { print_block(block); return }
    # A static helper the copy keeps with __attribute__((unused)).
    n = split(block, lines, "\n"); variant = ""
    for (j = 1; j < n; j++) {
        if (lines[j] ~ /^static /) sub(/^static /, "static __attribute__((unused)) ", lines[j])
        variant = variant lines[j] "\n"
    }
    if (index(corpus, variant) > 0) { print_block(variant); return }
    # A blanked body: the stub of every marked function the listing overlaps.
    stubs = 0
    for (p = 1; p <= nfiles && !stubs; p++) {
        path = file_list[p]
        found = index(reference[path], block)
        if (found == 0) continue
        for (s = 1; s <= spans; s++) {
            if (span_file[s] != path || span_end[s] <= found || span_start[s] >= found + length(block)) continue
            id = span_id[s]
            if (!chosen(id)) continue
            stubs++
            if (shown[span_marker[s]]) {
                emit("*(This listing, more of `" span_name[s] "`'s body, is left out: task " id " is yours to write.)*")
                continue
            }
            shown[span_marker[s]] = 1
            stub = function_after_marker(copied[path], span_marker[s])
            if (span_also[s]) {
                emit("*In your copy, `" span_name[s] "` goes with task " id ": it computes what the task asks for, so you")
                emit("write it too (`make check-" int(id) "` grades the task). The listing shows its stub.*")
            } else {
                emit("*In your copy, `" span_name[s] "` is task " id ", which you write (`make check-" int(id) "` grades it):")
                emit("the listing shows its stub.*")
            }
            emit("")
            print_block(stub)
        }
    }
    if (!stubs) print_block(block) # quoted from nowhere: tests/test_docs.c reports it
}
function print_block(text) {
    printf "```c\n%s```\n", text > out
}
# Prints the ★★ exercise that starts at page line `at`, with a line for the student when it names a
# blanked function, and moves i past it.
function exercise(at,    k, text, last, id, names, n, j, candidate, c, ids, m, note) {
    text = page[at]
    for (k = at + 1; k <= page_lines && page[k] ~ /^   / ; k++) text = text "\n" page[k]
    last = k - 1
    for (k = at; k <= last; k++) emit(page[k])
    i = last
    n = split(text, names, "`")
    note = ""
    for (j = 2; j <= n && note == ""; j += 2) {
        candidate = names[j]
        if (!(candidate in task_of_name) || names[j - 1] !~ /(^|[^A-Za-z])([Ii]n|of) $/) continue
        m = split(task_of_name[candidate], ids, " ")
        for (c = 1; c <= m; c++) {
            id = ids[c]
            if (!chosen(id) || (int(id) != chapter && index(text, name_file[candidate]) == 0)) continue
            note = "   *In your copy, `" candidate "` (" name_file[candidate] ") " \
                   (candidate == task_name[id] ? "is task " id : "goes with task " id) ", which you write: make this change " \
                   "in your own `" candidate "` once `make check-" int(id) "` says " id " is done. Code quoted here, and " \
                   "the numbers, are the reference's.*"
        }
    }
    if (note != "") emit(note)
}
