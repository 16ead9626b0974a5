/* A stop asked by the user (SIGINT, Ctrl-C, or SIGTERM): the handler only records the
 * signal; the time loop looks at it between steps and ends the run cleanly, so that what
 * was computed is written, marked interrupted (src/interrupt.f90). */
#include <signal.h>
#include <string.h>

static volatile sig_atomic_t voussoir_signal = 0;

static void record_signal(int sig) { voussoir_signal = sig; }

/* Catch SIGINT and SIGTERM from now on. Returns 0, or -1 if a handler could not be set. */
int voussoir_catch_stop_signals(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = record_signal;
    sigemptyset(&sa.sa_mask);
    if (sigaction(SIGINT, &sa, NULL) != 0) return -1;
    if (sigaction(SIGTERM, &sa, NULL) != 0) return -1;
    return 0;
}

/* The signal that asked to stop (0: none). */
int voussoir_stop_signal(void) { return (int)voussoir_signal; }
