// A file system that fills up, for tests that cannot mount one: loaded with LD_PRELOAD into the
// gale program, it lets GALE_FULL_DISK_BYTES bytes in all be written to regular files under the
// folder GALE_FULL_DISK_FOLDER, then fails every further write there with ENOSPC, the way a full
// disk does (the write that crosses the limit is cut short at the limit). Other files (stdout,
// stderr, pipes, files elsewhere) are untouched.
//
// It covers the write paths gale's writers use: write/writev/pwrite (OpenVDB through
// std::ofstream) and fwrite/fputs/fputc (libpng, giflib, OpenImageIO's file proxy, stdio). glibc's
// stdio buffers, so a real full disk shows up at the flush inside fwrite or fclose; the shim fails
// the fwrite itself, marks the stream's error flag, and makes its fflush and fclose fail too.
//
// With GALE_FULL_DISK_STATVFS=1 it also tells the truth about the space: statvfs of a path in
// the folder reports the bytes still allowed as free (f_bavail, f_bfree), so that free-space
// checks see the disk the writes will meet.

#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

static long long gLeft = -1;    // bytes still allowed; -1: not configured yet
static char gFolder[PATH_MAX];  // absolute, without a trailing slash
static int gConfigured = 0;

static void configure(void) {
    if (gConfigured) return;
    gConfigured = 1;
    const char* bytes = getenv("GALE_FULL_DISK_BYTES");
    const char* folder = getenv("GALE_FULL_DISK_FOLDER");
    if (!bytes || !folder || !realpath(folder, gFolder)) {
        gLeft = LLONG_MAX;
        return;
    }
    gLeft = atoll(bytes);
}

// True if fd is a regular file under the folder.
static int watched(int fd) {
    configure();
    if (gLeft == LLONG_MAX || fd < 0) return 0;
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) return 0;
    char link[64], target[PATH_MAX];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    const ssize_t n = readlink(link, target, sizeof target - 1);
    if (n <= 0) return 0;
    target[n] = '\0';
    const size_t len = strlen(gFolder);
    return strncmp(target, gFolder, len) == 0 && target[len] == '/';
}

// How many of `want` bytes may go to a watched file: all, a part, or none (then ENOSPC).
static size_t allow(size_t want) {
    const size_t ok = (long long)want <= gLeft ? want : (size_t)gLeft;
    gLeft -= (long long)ok;
    return ok;
}

// The next definition of `name` (libc's, or a sanitizer's interceptor before it).
#define REAL(name)                                  \
    static __typeof__(&name) real_##name = NULL; \
    if (!real_##name) real_##name = (__typeof__(&name))dlsym(RTLD_NEXT, #name)

ssize_t write(int fd, const void* buf, size_t count) {
    REAL(write);
    if (!watched(fd) || count == 0) return real_write(fd, buf, count);
    const size_t ok = allow(count);
    if (ok == 0) {
        errno = ENOSPC;
        return -1;
    }
    return real_write(fd, buf, ok);
}

ssize_t pwrite(int fd, const void* buf, size_t count, off_t offset) {
    REAL(pwrite);
    if (!watched(fd) || count == 0) return real_pwrite(fd, buf, count, offset);
    const size_t ok = allow(count);
    if (ok == 0) {
        errno = ENOSPC;
        return -1;
    }
    return real_pwrite(fd, buf, ok, offset);
}

ssize_t pwrite64(int fd, const void* buf, size_t count, off_t offset) {
    return pwrite(fd, buf, count, offset);
}

ssize_t writev(int fd, const struct iovec* iov, int iovcnt) {
    REAL(writev);
    if (!watched(fd)) return real_writev(fd, iov, iovcnt);
    // One piece at a time through write: a short write ends the call, as writev may.
    ssize_t total = 0;
    for (int i = 0; i < iovcnt; ++i) {
        if (iov[i].iov_len == 0) continue;
        const ssize_t n = write(fd, iov[i].iov_base, iov[i].iov_len);
        if (n < 0) return total > 0 ? total : -1;
        total += n;
        if ((size_t)n < iov[i].iov_len) break;
    }
    return total;
}

// Streams that hit the limit: their fflush and fclose fail as well.
enum { MAX_FAILED = 64 };
static FILE* gFailed[MAX_FAILED];

static void markFailed(FILE* f) {
    f->_flags |= _IO_ERR_SEEN;  // what ferror reports (glibc)
    for (int i = 0; i < MAX_FAILED; ++i)
        if (!gFailed[i] || gFailed[i] == f) {
            gFailed[i] = f;
            return;
        }
}

static int failed(FILE* f, int forget) {
    for (int i = 0; i < MAX_FAILED; ++i)
        if (gFailed[i] == f) {
            if (forget) gFailed[i] = NULL;
            return 1;
        }
    return 0;
}

size_t fwrite(const void* ptr, size_t size, size_t nmemb, FILE* f) {
    REAL(fwrite);
    if (size == 0 || nmemb == 0 || !watched(fileno(f))) return real_fwrite(ptr, size, nmemb, f);
    const size_t ok = allow(size * nmemb);
    const size_t items = ok / size;
    const size_t written = items > 0 ? real_fwrite(ptr, size, items, f) : 0;
    if (ok < size * nmemb) {
        markFailed(f);
        errno = ENOSPC;
    }
    return written;
}

int fputs(const char* s, FILE* f) {
    const size_t n = strlen(s);
    return fwrite(s, 1, n, f) == n ? 1 : EOF;
}

int fputc(int c, FILE* f) {
    const unsigned char b = (unsigned char)c;
    return fwrite(&b, 1, 1, f) == 1 ? c : EOF;
}

int putc(int c, FILE* f) { return fputc(c, f); }

int fflush(FILE* f) {
    REAL(fflush);
    const int r = real_fflush(f);
    if (f && failed(f, 0)) {
        errno = ENOSPC;
        return EOF;
    }
    return r;
}

int fclose(FILE* f) {
    REAL(fclose);
    const int wasFailed = failed(f, 1);
    const int r = real_fclose(f);
    if (wasFailed) {
        errno = ENOSPC;
        return EOF;
    }
    return r;
}

// Free space under the folder, as the writes will find it (GALE_FULL_DISK_STATVFS=1 only).
static void reportFree(const char* path, struct statvfs* buf) {
    configure();
    const char* on = getenv("GALE_FULL_DISK_STATVFS");
    if (gLeft == LLONG_MAX || !on || strcmp(on, "1") != 0) return;
    char target[PATH_MAX];
    if (!realpath(path, target)) return;
    const size_t len = strlen(gFolder);
    if (strncmp(target, gFolder, len) != 0 || (target[len] != '/' && target[len] != '\0')) return;
    const unsigned long block = buf->f_frsize ? buf->f_frsize : 4096;
    buf->f_bavail = buf->f_bfree = (fsblkcnt_t)(gLeft / (long long)block);
}

int statvfs(const char* path, struct statvfs* buf) {
    REAL(statvfs);
    const int r = real_statvfs(path, buf);
    if (r == 0) reportFree(path, buf);
    return r;
}
