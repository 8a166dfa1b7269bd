// ChildServer: what the child sends comes back whole; a child that dies is told of, this process
// goes on, and the next request is served by a new child.
#include "harness/import/child_server.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace obscura::harness {
namespace {

// Requests: "echo X" sends X back in two frames (its first two characters, then the rest), "pid" sends the child's pid, "segv" dies by
// SIGSEGV after sending "before", "exit N" exits with status N, "big" sends 8 MiB.
std::string bigReply() {
    std::string big(8 << 20, '\0');
    for (size_t i = 0; i < big.size(); ++i) big[i] = char(i * 2654435761u >> 24);
    return big;
}

char processState(pid_t pid) {
    std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
    std::string line;
    std::getline(stat, line);
    const size_t name = line.rfind(')');
    return name == std::string::npos || name + 2 >= line.size() ? '?' : line[name + 2];
}

void work(const std::string& request, ReplyChannel& reply) {
    if (request.starts_with("echo ")) {
        reply.send(request.substr(5, 2));
        reply.send(request.substr(7));
    } else if (request == "pid") {
        reply.send(std::to_string(::getpid()));
    } else if (request == "segv") {
        reply.send("before");
        // Not through a sanitizer's handler, which would turn the crash into an exit status.
        std::signal(SIGSEGV, SIG_DFL);
        std::raise(SIGSEGV);
        reply.send("after");
    } else if (request.starts_with("exit ")) {
        std::_Exit(std::stoi(request.substr(5)));
    } else if (request == "big") {
        reply.send(bigReply());
    }
}

TEST(ChildServer, WhatTheChildSendsComesBackInOrder) {
    ChildServer server(work);
    const ChildReply reply = server.call("echo first second");
    EXPECT_EQ(reply.end, ChildReply::End::Answered) << reply.how;
    EXPECT_EQ(reply.frames, (std::vector<std::string>{"fi", "rst second"}));
    EXPECT_EQ(server.call("echo again").frames, (std::vector<std::string>{"ag", "ain"}));
}

TEST(ChildServer, OneChildServesRequestsUntilItDies) {
    ChildServer server(work);
    const std::string first = server.call("pid").frames.at(0);
    EXPECT_NE(first, std::to_string(::getpid()));
    EXPECT_EQ(server.call("pid").frames.at(0), first);
}

// Far more than a socket buffers: this process reads while the child writes.
TEST(ChildServer, MoreThanASocketHoldsComesBackWhole) {
    ChildServer server(work);
    const ChildReply reply = server.call("big");
    EXPECT_EQ(reply.end, ChildReply::End::Answered) << reply.how;
    ASSERT_EQ(reply.frames.size(), 1u);
    EXPECT_TRUE(reply.frames[0] == bigReply()) << reply.frames[0].size() << " bytes came back";
}

TEST(ChildServer, AChildKilledByASignalIsToldAndTheNextRequestGetsANewOne) {
    ChildServer server(work);
    const std::string before = server.call("pid").frames.at(0);
    const ChildReply reply = server.call("segv");
    EXPECT_EQ(reply.end, ChildReply::End::ChildDied);
    EXPECT_EQ(reply.frames, std::vector<std::string>{"before"});
    EXPECT_EQ(reply.how, "signal 11 (Segmentation fault)");
    const ChildReply next = server.call("pid");
    EXPECT_EQ(next.end, ChildReply::End::Answered);
    EXPECT_NE(next.frames.at(0), before);
}

TEST(ChildServer, AChildThatExitsIsToldItsStatus) {
    ChildServer server(work);
    const ChildReply reply = server.call("exit 3");
    EXPECT_EQ(reply.end, ChildReply::End::ChildDied);
    EXPECT_EQ(reply.how, "exit status 3");
}

// Killed from outside while idle: the request goes to a new child.
TEST(ChildServer, AChildKilledBetweenRequestsIsReplaced) {
    ChildServer server(work);
    const pid_t child = std::stoi(server.call("pid").frames.at(0));
    ASSERT_EQ(::kill(child, SIGKILL), 0);
    // Dead (a zombie, its socket closed) before the next request, or the test would race the kill.
    while (processState(child) != 'Z') std::this_thread::sleep_for(std::chrono::milliseconds(1));
    const ChildReply reply = server.call("echo still here");
    EXPECT_EQ(reply.end, ChildReply::End::Answered) << reply.how;
    EXPECT_EQ(reply.frames, (std::vector<std::string>{"st", "ill here"}));
}

}  // namespace
}  // namespace obscura::harness
