// A child process, forked from this one, that answers requests one at a time: a crash inside the
// work it does (a third-party reader on a malformed file) ends the child, not the host. The next
// request forks a new one. Forking once and not per request keeps a request cheap also in a large
// process, where copying the page tables for each would cost milliseconds.
//
// The child is a copy of this process with only the forking thread. It must use nothing another
// thread could have held locked at the fork: only the work's own code, malloc (which glibc makes
// safe across fork) and its socket. It ends with _exit, so no atexit handler or static destructor of
// the host runs twice.
#pragma once

#include <sys/types.h>

#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace obscura::harness {

// The child's side of a reply.
class ReplyChannel {
public:
    explicit ReplyChannel(int fd) : fd_(fd) {}
    // Each send reaches the parent as one frame, whole and in order, even if the child dies after it.
    void send(const std::string& frame);

private:
    int fd_;
};

struct ChildReply {
    enum class End { Answered, ChildDied, NoChild } end = End::NoChild;
    std::vector<std::string> frames;  // what the work sent, one per send, up to where it stopped
    std::string how;    // how the child died ("signal 11 (Segmentation fault)", "exit status 1"),
                        // or why none could be started
};

class ChildServer {
public:
    using Work = std::function<void(const std::string& request, ReplyChannel& reply)>;

    explicit ChildServer(Work work) : work_(std::move(work)) {}
    ~ChildServer();
    ChildServer(const ChildServer&) = delete;
    ChildServer& operator=(const ChildServer&) = delete;

    // Runs work(request) in the child; callers of several threads take turns.
    ChildReply call(const std::string& request);

private:
    bool start(std::string& why);
    void serve(int socket);
    std::string stop();  // closes this end, waits for the child and says how it ended
    std::string howItEnded();

    Work work_;
    std::mutex mutex_;
    pid_t pid_ = -1;
    int socket_ = -1;  // this process's end of the socket pair the child serves
};

}  // namespace obscura::harness
