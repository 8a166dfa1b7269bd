#include "harness/import/child_server.h"

#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <optional>

namespace obscura::harness {

namespace {

// One stream socket pair carries frames both ways: a 64-bit length, then that many bytes. A reply
// is any number of frames (ReplyChannel::send) ended by the length kReplyEnd alone. A socket and not a pipe because a send
// to a peer that has died must fail (MSG_NOSIGNAL), not raise SIGPIPE and end the host.

bool writeAll(int fd, const char* data, size_t size) {
    while (size > 0) {
        const ssize_t written = ::send(fd, data, size, MSG_NOSIGNAL);
        if (written < 0 && errno == EINTR) continue;
        if (written <= 0) return false;
        data += written;
        size -= size_t(written);
    }
    return true;
}

bool readAll(int fd, char* data, size_t size) {
    while (size > 0) {
        const ssize_t got = ::read(fd, data, size);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) return false;
        data += got;
        size -= size_t(got);
    }
    return true;
}

constexpr uint64_t kReplyEnd = ~uint64_t(0);

bool writeFrame(int fd, const std::string& bytes) {
    const uint64_t size = bytes.size();
    return writeAll(fd, reinterpret_cast<const char*>(&size), sizeof size) && writeAll(fd, bytes.data(), bytes.size());
}

// A frame, or nullopt at the end of the stream or of a reply (`replyEnded` then says which).
std::optional<std::string> readFrame(int fd, bool* replyEnded = nullptr) {
    uint64_t size = 0;
    if (!readAll(fd, reinterpret_cast<char*>(&size), sizeof size)) return std::nullopt;
    if (size == kReplyEnd) {
        if (replyEnded) *replyEnded = true;
        return std::nullopt;
    }
    std::string bytes(size, '\0');
    if (!readAll(fd, bytes.data(), size)) return std::nullopt;
    return bytes;
}

}  // namespace

void ReplyChannel::send(const std::string& frame) { writeFrame(fd_, frame); }

ChildServer::~ChildServer() {
    std::lock_guard lock(mutex_);
    if (pid_ >= 0) stop();
}

bool ChildServer::start(std::string& why) {
    int ends[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, ends) != 0) {
        why = std::string("cannot make a socket pair: ") + std::strerror(errno);
        return false;
    }
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(ends[0]);
        serve(ends[1]);
        ::_exit(0);
    }
    ::close(ends[1]);
    if (pid < 0) {
        why = std::string("cannot start a process: ") + std::strerror(errno);
        ::close(ends[0]);
        return false;
    }
    pid_ = pid;
    socket_ = ends[0];
    return true;
}

void ChildServer::serve(int socket) {
    // A crash here is reported to the user as an error; a core file of it would only fill disks.
    const rlimit noCore{0, 0};
    ::setrlimit(RLIMIT_CORE, &noCore);
    // The parent closing its end (or ending) ends the loop.
    ReplyChannel reply(socket);
    while (std::optional<std::string> request = readFrame(socket)) {
        work_(*request, reply);
        const uint64_t end = kReplyEnd;
        if (!writeAll(socket, reinterpret_cast<const char*>(&end), sizeof end)) return;
    }
}

std::string ChildServer::howItEnded() {
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    if (WIFSIGNALED(status))
        return "signal " + std::to_string(WTERMSIG(status)) + " (" + ::strsignal(WTERMSIG(status)) + ")";
    return "exit status " + std::to_string(WEXITSTATUS(status));
}

std::string ChildServer::stop() {
    ::close(socket_);
    socket_ = -1;
    return howItEnded();
}

ChildReply ChildServer::call(const std::string& request) {
    std::lock_guard lock(mutex_);
    ChildReply reply;
    if (pid_ < 0 && !start(reply.how)) return reply;
    reply.end = ChildReply::End::ChildDied;
    // A child that died between requests (killed from outside) is replaced once.
    if (!writeFrame(socket_, request)) {
        stop();
        if (!start(reply.how)) {
            reply.end = ChildReply::End::NoChild;
            return reply;
        }
        if (!writeFrame(socket_, request)) {
            reply.how = stop();
            return reply;
        }
    }
    bool replyEnded = false;
    while (std::optional<std::string> frame = readFrame(socket_, &replyEnded)) reply.frames.push_back(std::move(*frame));
    if (replyEnded) {
        reply.end = ChildReply::End::Answered;
        return reply;
    }
    reply.how = stop();
    return reply;
}

}  // namespace obscura::harness
