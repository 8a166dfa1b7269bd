// A scripted sequence of the viewer's input events (`obscura view --script FILE`), for tests and
// demos: the same handlers as the window's mouse and keys, and a few waits. One event per line;
// `#` starts a comment.
//   press BUTTON X Y [shift] [ctrl]   BUTTON: left, middle, right
//   move X Y
//   release BUTTON X Y
//   click X Y [ctrl]                  press and release without moving: a pick (ctrl: focus there)
//   scroll STEPS                      dolly, positive towards the target
//   key NAME                          F frame all, H HUD, W A S D Q E fly, 0 free camera, 1-9 a scene camera
//   aov NAME                          show display, depth, normal, motion or primId
//   set KEY=VALUE                     a render setting, as the HUD's toggles and lens controls set them
//   lens NAME VALUE                   focalLength, fStop, focusDistance or apertureBlades of the free camera
//   frames N                          render N frames
//   wait-converged                    render until temporal AA has converged
//   wait-reload                       wait until a file of the scene changes on disk and it is read again
//   screenshot PATH                   write the window as it is shown to PATH (PNG)
//   close                             close the window, as its close button does
#pragma once

#include <istream>
#include <string>
#include <variant>
#include <vector>

namespace obscura::harness::view {

struct ScriptEvent {
    std::string verb;
    std::vector<std::string> words;  // the arguments as written
    std::vector<double> numbers;     // the arguments that are numbers, in order
    int line = 0;
    bool has(const std::string& word) const;
};

// The events of a script, or the first line that is not one ("NAME:LINE: why").
std::variant<std::vector<ScriptEvent>, std::string> parseInputScript(std::istream& in, const std::string& name);
// The events of the script file at `path` (parseInputScript, named by its path).
std::variant<std::vector<ScriptEvent>, std::string> readInputScript(const std::string& path);

}  // namespace obscura::harness::view
