// Writing the window's back buffer as a PNG (--frames N --screenshot FILE).
#pragma once

#include <filesystem>
#include <string>

namespace rigidlab::sandbox {

// Reads the back buffer (call after the frame is drawn, before the buffer swap) and writes it as
// an 8-bit RGB PNG, top row first. The file appears complete or not at all (temporary + rename).
// Returns false with `error` set on failure.
bool writeScreenshot(const std::filesystem::path& file, int width, int height, std::string& error);

}  // namespace rigidlab::sandbox
