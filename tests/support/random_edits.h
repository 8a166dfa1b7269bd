// A scene under random edits through the ABI, for the soak test and the soak benchmark:
// each frame changes a few of transforms, points, materials, lights, prims added and removed, the
// render size and render settings, then renders. Deterministic for a seed.
#pragma once

#include "tests/support/in_memory_host.h"

#include <random>
#include <set>
#include <string>

namespace obscura::test {

class RandomEditScene {
public:
    // Render sizes are drawn around width x height (small: the soak runs on lavapipe).
    RandomEditScene(InMemoryHost& host, uint32_t seed, int width, int height);
    // A few random edits, then one render; returns its status.
    ObscuraStatus editAndRender();
    int width() const { return width_; }
    int height() const { return height_; }

private:
    void addCard(int index);
    void editOnce();

    InMemoryHost& host_;
    std::mt19937 random_;
    int baseWidth_, baseHeight_, width_, height_;
    std::set<int> cards_;  // indices of the cards in the scene
};

}  // namespace obscura::test
