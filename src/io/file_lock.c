/* One sweep per result file: an advisory lock (flock) on FILE.lock, held while the sweep
 * runs. The system drops it when the process ends, however it ends (kill -9 included),
 * so a lock file left behind by a killed sweep never blocks the rerun that continues it.
 * Bound to Fortran by src/hdf5/file_lock.f90. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <sys/file.h>
#include <unistd.h>

/* Lock `path` (created if absent). Returns the descriptor (>= 0); -1 when another process
 * holds the lock; -2 when the lock file cannot be made (message in `message`). */
int voussoir_lock_file(const char *path, char *message, size_t message_len) {
  int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    snprintf(message, message_len, "%s", strerror(errno));
    return -2;
  }
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    int busy = errno == EWOULDBLOCK;
    snprintf(message, message_len, "%s", strerror(errno));
    close(fd);
    return busy ? -1 : -2;
  }
  /* Who holds it, for a person reading the file. */
  char who[64];
  int n = snprintf(who, sizeof who, "pid %ld\n", (long)getpid());
  if (ftruncate(fd, 0) == 0 && n > 0) {
    ssize_t w = write(fd, who, (size_t)n);
    (void)w;
  }
  return fd;
}

/* Remove the lock file and release the lock. */
void voussoir_unlock_file(int fd, const char *path) {
  if (fd < 0) return;
  unlink(path);
  close(fd);
}
