/* clock.h: the clocks the programs time themselves with: the wall clock for the render, the builds of
 * the structures and the whole run (chapter 1 on), and the processor time for the benchmark. */
#ifndef WHITTED_CLOCK_H
#define WHITTED_CLOCK_H

/* Returns the monotonic wall clock's reading in seconds since an arbitrary fixed point: the difference
 * of two readings is the time that passed between them, whatever the system's date does meanwhile. */
double clock_seconds(void);

/* Returns the processor time the whole process has used so far, all its threads together, in seconds:
 * on a machine shared with other work it counts only the time this process ran (bench/bench_accel.c). */
double clock_processor_seconds(void);

#endif
