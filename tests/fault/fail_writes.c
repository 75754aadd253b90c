// LD_PRELOAD shim for tests/e2e/output_faults_test.cpp: a disk that fills up
// after PASSTRACE_FAIL_WRITES_AFTER bytes. Writes to regular files (not the
// standard streams) pass until that many bytes have gone to them; the write
// that crosses the limit is cut short there, as a full disk cuts it, and
// every later one fails with ENOSPC. write, pwrite, writev and fwrite are
// wrapped: what passtrace's own code and the libraries it links call (stdio
// writes its buffers through glibc's internal write, so fwrite is wrapped
// itself). Without the variable the shim does nothing.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

static long long budget(void) {
  const char* limit = getenv("PASSTRACE_FAIL_WRITES_AFTER");
  return limit ? atoll(limit) : -1;
}

static long long written;  // bytes gone to regular files so far; one thread writes the outputs

// How many of `size` bytes to fd may pass: all of them, a part, or none
// (-1 with errno = ENOSPC).
static ssize_t allowed(int fd, size_t size) {
  const long long limit = budget();
  struct stat info;
  if (limit < 0 || fd <= 2 || size == 0 || fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) return (ssize_t)size;
  const long long left = limit - written;
  if (left <= 0) {
    errno = ENOSPC;
    return -1;
  }
  const ssize_t n = (long long)size < left ? (ssize_t)size : (ssize_t)left;
  written += n;
  return n;
}

#define NEXT(name) ((__typeof__(&name))dlsym(RTLD_NEXT, #name))

ssize_t write(int fd, const void* buf, size_t size) {
  const ssize_t n = allowed(fd, size);
  return n < 0 ? n : NEXT(write)(fd, buf, (size_t)n);
}

ssize_t pwrite(int fd, const void* buf, size_t size, off_t offset) {
  const ssize_t n = allowed(fd, size);
  return n < 0 ? n : NEXT(pwrite)(fd, buf, (size_t)n, offset);
}

ssize_t pwrite64(int fd, const void* buf, size_t size, off_t offset) { return pwrite(fd, buf, size, offset); }

ssize_t writev(int fd, const struct iovec* iov, int count) {
  size_t size = 0;
  for (int i = 0; i < count; ++i) size += iov[i].iov_len;
  const ssize_t n = allowed(fd, size);
  if (n < 0) return n;
  if ((size_t)n == size) return NEXT(writev)(fd, iov, count);
  // Cut short: the first n bytes, as one write.
  ssize_t done = 0;
  for (int i = 0; i < count && done < n; ++i) {
    const size_t part = iov[i].iov_len < (size_t)(n - done) ? iov[i].iov_len : (size_t)(n - done);
    const ssize_t w = NEXT(write)(fd, iov[i].iov_base, part);
    if (w < 0) return done > 0 ? done : w;
    done += w;
  }
  return done;
}

size_t fwrite(const void* buf, size_t size, size_t count, FILE* stream) {
  if (size == 0) return NEXT(fwrite)(buf, size, count, stream);
  const ssize_t n = allowed(fileno(stream), size * count);
  if (n < 0) return 0;
  return NEXT(fwrite)(buf, size, (size_t)n / size, stream);
}
