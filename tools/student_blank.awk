# student_blank.awk: replaces the body of every function marked "/* TASK N.K: what */" whose task is
# chosen by a stub that compiles, keeps the signature and says which task it is (the coursework kit;
# tools/student.sh runs it on every C file of a student copy).
#
#   awk -v tasks="2.1 5.1" -f tools/student_blank.awk common/sphere.c    (tasks="all": every marked task, "none": none)
#
# A function elsewhere that computes what a task asks for, and so would give its answer away, carries a
# second marker tied to the task, "/* TASK N.K ALSO: what */": it is blanked whenever task N.K is, and its
# stub says so. tools/student.sh --list lists only the tasks' own markers.
#
# The stub casts every parameter to void and returns a harmless zero value. A static helper that only
# the blanked body called would be "defined but not used", an error under -Werror (clang says so of a
# static inline function too): a second pass
# marks such helpers __attribute__((unused)), so they stay in the file for the student to call.
function chosen(id) { return tasks == "all" || (tasks != "none" && index(" " tasks " ", " " id " ") > 0) }
function trim(s) { gsub(/^[ \t\n]+|[ \t\n]+$/, "", s); return s }
function stub(signature, id, what, also,    open, shut, prefix, name, type, params, n, k, p, out, ret) {
    gsub(/__attribute__\(\([a-z_]*\)\)/, "", signature)
    open = index(signature, "(")
    prefix = substr(signature, 1, open - 1)
    shut = match(signature, /\)[ \t\n]*\{[ \t]*$/)
    params = substr(signature, open + 1, shut - open - 1)
    gsub(/(^|[ \t])(static|inline|extern)[ \t]/, " ", prefix); gsub(/(^|[ \t])(static|inline|extern)[ \t]/, " ", prefix)
    gsub(/(^|[ \t])[A-Z][A-Z0-9_]+[ \t]/, " ", prefix) # a function attribute's macro, such as AVX2
    prefix = trim(prefix)
    name = prefix; sub(/^.*[ *]/, "", name)
    type = trim(substr(prefix, 1, length(prefix) - length(name)))
    if (also)
        out = "    /* TODO (chapter " int(id) ", with task " id "): " what ".\n" \
              "     * It computes what task " id " asks for, so it would give the answer away: it is blanked\n" \
              "     * with the task, and yours to write once make check-" int(id) " says " id " is done. Its contract\n" \
              "     * is in the comment above this function or above its declaration in the header. */\n"
    else
        out = "    /* TODO (chapter " int(id) ", task " id "): " what ".\n" \
              "     * Its contract is in the comment above this function or above its declaration in the header;\n" \
              "     * make check-" int(id) " grades it. */\n"
    n = split(params, p, ",")
    for (k = 1; k <= n; k++) {
        p[k] = trim(p[k]); sub(/\[[^]]*\]$/, "", p[k])
        if (p[k] == "void" || p[k] == "") continue
        sub(/^.*[ *]/, "", p[k])
        out = out "    (void)" p[k] ";\n"
    }
    if (type == "void") ret = ""
    else if (type == "bool") ret = "false"
    else if (type ~ /^(double|float)$/) ret = "0.0"
    else if (type ~ /^(int|long|size_t|u?int[0-9]+_t|unsigned)$/ || type ~ /\*$/) ret = (type ~ /\*$/ ? "NULL" : "0")
    else if (type == "vec3") ret = "vec3_make(0, 0, 0)"
    else ret = "(" type "){0}"
    if (ret != "") out = out "    return " ret ";\n"
    return out
}
FNR == 1 { nlines = 0 }
{ line[++nlines] = $0 }
END {
    out = 0
    for (i = 1; i <= nlines; i++) {
        text[++out] = line[i]
        if (!match(line[i], /^\/\* TASK [0-9]+\.[0-9]+( ALSO)?: .* \*\/$/)) continue
        also = line[i] ~ /^\/\* TASK [0-9.]+ ALSO: /
        id = line[i]; sub(/^\/\* TASK /, "", id); sub(/( ALSO)?:.*$/, "", id)
        what = line[i]; sub(/^\/\* TASK [0-9.]+( ALSO)?: /, "", what); sub(/ \*\/$/, "", what)
        if (!chosen(id)) continue
        signature = ""
        for (i++; i <= nlines; i++) {
            text[++out] = line[i]
            signature = signature (signature == "" ? "" : "\n") line[i]
            if (line[i] ~ /\{[ \t]*$/) break
        }
        if (i > nlines) { print FILENAME ": TASK " id ": no function body follows the marker" > "/dev/stderr"; exit 1 }
        for (i++; i <= nlines && line[i] != "}"; i++) ;
        if (i > nlines) { print FILENAME ": TASK " id ": the body never ends (a } alone on a line)" > "/dev/stderr"; exit 1 }
        text[++out] = stub(signature, id, what, also) "}"
    }
    # Static helpers nothing calls any more: keep them, marked unused.
    all = ""
    for (k = 1; k <= out; k++) all = all text[k] "\n"
    gsub(/\/\*([^*]|\*+[^*\/])*\*+\//, " ", all) # comments do not count as uses ("may still spawn")
    for (k = 1; k <= out; k++) {
        head = text[k]; gsub(/__attribute__\(\([^)]*\)\)/, "", head) # such as always_inline
        if (!match(head, /^static [^(=;]*[ *][A-Za-z_][A-Za-z0-9_]*\(/)) continue
        name = substr(head, 1, RLENGTH - 1); sub(/^.*[ *]/, "", name)
        rest = all; uses = 0
        while ((at = match(rest, "[^A-Za-z0-9_]" name "[^A-Za-z0-9_]")) > 0) { uses++; rest = substr(rest, at + RLENGTH - 1) }
        if (uses == 1) sub(/^static /, "static __attribute__((unused)) ", text[k])
    }
    for (k = 1; k <= out; k++) print text[k]
}
