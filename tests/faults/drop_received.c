/* A FAULT INJECTOR for the tests, named as such: lose chosen datagrams a process receives.
 *
 * A loaded host loses UDP datagrams when a socket's receive buffer overflows (this 2-core
 * machine counts millions of such drops in /proc/net/snmp, RcvbufErrors, in bursts while a
 * test starts its nodes). Which datagram is lost cannot be chosen on the real thing, so this
 * library, loaded with LD_PRELOAD, wraps recvmsg(2) (what Cyclone DDS receives with): every
 * DROP_EVERY-th datagram that contains the bytes DROP_MARK is taken from the socket and
 * thrown away, as the kernel would have. One line per datagram lost is appended to
 * DROP_LOG. Built by the tests with gcc (tests/test_ros2_lost_replies.py).
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>

static ssize_t (*real_recvmsg)(int, struct msghdr *, int);
static pthread_mutex_t lock = PTHREAD_MUTEX_INITIALIZER;
static unsigned long seen;

static int marked(const struct msghdr *msg, size_t n, const char *mark) {
    size_t left = n;
    for (size_t i = 0; i < (size_t)msg->msg_iovlen && left > 0; i++) {
        size_t len = msg->msg_iov[i].iov_len < left ? msg->msg_iov[i].iov_len : left;
        if (memmem(msg->msg_iov[i].iov_base, len, mark, strlen(mark)) != NULL)
            return 1;
        left -= len;
    }
    return 0;
}

ssize_t recvmsg(int fd, struct msghdr *msg, int flags) {
    if (real_recvmsg == NULL)
        real_recvmsg = (ssize_t (*)(int, struct msghdr *, int))dlsym(RTLD_NEXT, "recvmsg");
    const char *mark = getenv("DROP_MARK");
    unsigned long every = strtoul(getenv("DROP_EVERY") ? getenv("DROP_EVERY") : "0", NULL, 10);
    for (;;) {
        ssize_t n = real_recvmsg(fd, msg, flags);
        if (n <= 0 || mark == NULL || every == 0 || !marked(msg, (size_t)n, mark))
            return n;
        pthread_mutex_lock(&lock);
        int drop = ++seen % every == 0;
        pthread_mutex_unlock(&lock);
        if (!drop)
            return n;
        const char *log = getenv("DROP_LOG");
        FILE *f = log ? fopen(log, "a") : NULL;
        if (f != NULL) {
            fprintf(f, "dropped a datagram of %zd bytes\n", n);
            fclose(f);
        }
    }
}
