/* Writing a finished result file to disk, with every error seen.
 *
 * Fortran's buffered I/O may report a full disk late or not at all (gfortran lets a
 * failed flush at CLOSE pass), so the bytes of a result file go through write(2),
 * fsync(2) and close(2) here, each checked. A write past the process's file-size limit
 * (ulimit -f) must fail the same way instead of killing the program with SIGXFSZ. */
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stddef.h>
#include <string.h>
#include <unistd.h>

void voussoir_report_file_limits(void) { signal(SIGXFSZ, SIG_IGN); }

/* Write n bytes to path (created or truncated). Returns 0, or errno with its text in
 * message (message_len bytes, NUL-terminated). */
int voussoir_write_file(const char *path, const void *bytes, size_t n, char *message, size_t message_len) {
  const char *p = bytes;
  int err = 0;
  int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0666);
  if (fd < 0) {
    err = errno;
  } else {
    while (n > 0 && err == 0) {
      ssize_t k = write(fd, p, n);
      if (k < 0) {
        if (errno != EINTR) err = errno;
      } else {
        p += k;
        n -= (size_t)k;
      }
    }
    if (err == 0 && fsync(fd) != 0 && errno != EINVAL) err = errno;
    if (close(fd) != 0 && err == 0) err = errno;
  }
  if (err != 0 && message_len > 0) {
    strncpy(message, strerror(err), message_len - 1);
    message[message_len - 1] = '\0';
  }
  return err;
}
