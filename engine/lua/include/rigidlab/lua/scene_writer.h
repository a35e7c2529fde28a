// Saving a world as a Lua scene file that loads back to the same state (sandbox "Save").
//
// The file holds data only: a `scene` settings table, a `data` table of bodies (shapes, materials,
// filters, type and options, state), joints, built-in springs and dampers, and a PopulateWorld
// that hands the data to the scripts/saved_world.lua module (format 3; it reads 1 and 2 too).
// Loaded, it gives the same bodies, shapes and joints in the same order, with the same positions,
// angles, velocities, masses and shapes bit for bit, and joints that read the same anchors, angles
// and translations to rounding (the scene API takes anchors in world coordinates, from which the
// joint's frames in its bodies are computed again); a world saved before it ran steps bit for bit
// like the original. What cannot be written (code forces,
// bodies without shapes, joints the scene API cannot make) is named in a comment at the end. It is written atomically: a temporary file in the same directory,
// flushed and fsync'ed, renamed over the target, then the directory fsync'ed; a save killed
// mid-write leaves the old file or the new one, never a torn one.
#pragma once

#include <filesystem>
#include <string>

#include "rigidlab/lua/scene.h"
#include "rigidlab/world.h"

namespace rigidlab::lua {

// The scene file's text. Numbers are written in their shortest form that reads back to the same bits (std::to_chars).
std::string sceneSource(const World& world, const SceneSettings& settings);

// Writes sceneSource() to `path` atomically. Throws SceneError("<path>: <reason>") on failure,
// leaving any existing file untouched and no temporary file behind. A text longer than
// `max_bytes` (the largest scene file the loader reads, ScriptLimits::source_bytes) is refused
// before anything is written: rigidlab must open what it saves.
void saveScene(const World& world, const SceneSettings& settings, const std::filesystem::path& path,
               size_t max_bytes = ScriptLimits{}.source_bytes);

// Temporary files a killed save may have left next to `path`'s directory entries ("*.rigidlab-tmp-*");
// removes them. The sandbox calls it at start; the file watcher ignores such names.
void removeStaleTemporaries(const std::filesystem::path& directory);
bool isTemporaryName(const std::filesystem::path& file);

}  // namespace rigidlab::lua
