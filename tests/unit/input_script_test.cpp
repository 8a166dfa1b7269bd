// The viewer's input scripts (harness/view/input_script.h): every event with its arguments, and a
// line that is not an event named with its line number.
#include "harness/view/input_script.h"

#include <gtest/gtest.h>

#include <sstream>

namespace obscura::harness::view {
namespace {

std::vector<ScriptEvent> parsed(const std::string& text) {
    std::istringstream in(text);
    auto result = parseInputScript(in, "demo.script");
    if (auto* problem = std::get_if<std::string>(&result)) ADD_FAILURE() << *problem;
    return std::get_if<std::vector<ScriptEvent>>(&result) ? std::get<std::vector<ScriptEvent>>(result)
                                                           : std::vector<ScriptEvent>{};
}

std::string problemOf(const std::string& text) {
    std::istringstream in(text);
    auto result = parseInputScript(in, "demo.script");
    return std::holds_alternative<std::string>(result) ? std::get<std::string>(result) : "(parsed)";
}

TEST(InputScript, EveryEventWithItsWordsNumbersAndLine) {
    const auto events = parsed(
        "# a demo\n"
        "key H                  # the HUD off\n"
        "\n"
        "press left 32 24 shift\n"
        "move 40 24\n"
        "release left 40.5 24\n"
        "click 16 24 ctrl\n"
        "scroll -2\n"
        "aov normal\n"
        "set taa=off\n"
        "lens fStop 2.8\n"
        "frames 3\n"
        "wait-converged\n"
        "wait-reload\n"
        "screenshot shot.png\n"
        "close\n");
    ASSERT_EQ(events.size(), 14u);
    const std::vector<std::string> verbs = {"key",    "press", "move", "release", "click",          "scroll",      "aov",
                                            "set",    "lens",  "frames", "wait-converged", "wait-reload", "screenshot",
                                            "close"};
    for (size_t i = 0; i < verbs.size(); ++i) EXPECT_EQ(events[i].verb, verbs[i]);
    EXPECT_EQ(events[0].words, std::vector<std::string>{"H"});
    EXPECT_EQ(events[0].line, 2);
    EXPECT_EQ(events[1].line, 4);  // the blank line and the comment still count
    EXPECT_EQ(events[1].words, (std::vector<std::string>{"left", "32", "24", "shift"}));
    EXPECT_EQ(events[1].numbers, (std::vector<double>{32, 24}));
    EXPECT_TRUE(events[1].has("shift"));
    EXPECT_FALSE(events[1].has("ctrl"));
    EXPECT_EQ(events[3].numbers, (std::vector<double>{40.5, 24}));
    EXPECT_TRUE(events[4].has("ctrl"));
    EXPECT_EQ(events[5].numbers, std::vector<double>{-2});
    EXPECT_EQ(events[7].words, std::vector<std::string>{"taa=off"});
    EXPECT_EQ(events[8].words[0], "fStop");
    EXPECT_EQ(events[8].numbers, std::vector<double>{2.8});
    EXPECT_EQ(events[9].numbers, std::vector<double>{3});
    EXPECT_TRUE(events[10].words.empty());
    EXPECT_EQ(events[12].words, std::vector<std::string>{"shot.png"});
    EXPECT_EQ(events[13].line, 16);
}

TEST(InputScript, AnUnknownEventIsNamedWithItsLine) {
    EXPECT_EQ(problemOf("key H\n\njump 3\n"), "demo.script:3: unknown event 'jump'");
}

TEST(InputScript, AnEventShortOfArgumentsIsNamedWithItsLine) {
    EXPECT_EQ(problemOf("move 40\n"), "demo.script:1: 'move' needs more arguments");
    EXPECT_EQ(problemOf("close\nclick 16\n"), "demo.script:2: 'click' needs more arguments");
    EXPECT_EQ(problemOf("scroll up\n"), "demo.script:1: 'scroll' needs more arguments");
    EXPECT_EQ(problemOf("key\n"), "demo.script:1: 'key' needs more arguments");
    EXPECT_EQ(problemOf("screenshot # no path\n"), "demo.script:1: 'screenshot' needs more arguments");
    EXPECT_EQ(problemOf("lens fStop\n"), "demo.script:1: 'lens' needs more arguments");
    EXPECT_EQ(problemOf("press 32\n"), "demo.script:1: 'press' needs more arguments");
}

TEST(InputScript, AScriptThatCannotBeReadSaysSo) {
    auto result = readInputScript("/nonexistent/demo.script");
    ASSERT_TRUE(std::holds_alternative<std::string>(result));
    EXPECT_EQ(std::get<std::string>(result), "/nonexistent/demo.script: cannot read the script");
}

}  // namespace
}  // namespace obscura::harness::view
