/* clock.h: the one clock the programs time themselves with: the render, the builds of the structures,
 * the whole run (chapter 1 on). */
#ifndef WHITTED_CLOCK_H
#define WHITTED_CLOCK_H

/* Returns the monotonic wall clock's reading in seconds since an arbitrary fixed point: the difference
 * of two readings is the time that passed between them, whatever the system's date does meanwhile. */
double clock_seconds(void);

#endif
