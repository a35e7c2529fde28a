// Text that comes from a scene (body names, the title, draw:text, print lines, error messages):
// how much of it the host copies, and how it is shown. A scene is hostile (docs/security.md):
// its strings could be gigabytes long, or hold terminal escape sequences ("\27[2J") and bytes that
// are not UTF-8, which would clear a terminal or make --json output unparseable.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace rigidlab::lua {

// Longest strings the host copies out of a scene. Names and titles are data (a longer one is an
// error naming the field); draw texts, print lines and error messages are cut.
inline constexpr size_t kNameBytes = 256;       // body name
inline constexpr size_t kTitleBytes = 256;      // scene.title
inline constexpr size_t kDrawTextBytes = 1024;  // one draw:text
inline constexpr size_t kPrintBytes = 4096;     // one print() call
inline constexpr size_t kMessageBytes = 4096;   // an error message

// `text` made safe to show: control characters (C0 other than those in `keep`, DEL, and the C1
// controls U+0080–U+009F) as \n, \r, \t or \xHH, bytes that are not part of valid UTF-8 as \xHH,
// and cut after `max_bytes` bytes of output with "... (N more bytes)". Valid UTF-8 text without
// control characters comes back unchanged.
std::string displayText(std::string_view text, size_t max_bytes, std::string_view keep = "");

// `text` with every byte that is not part of valid UTF-8 replaced by U+FFFD (for JSON, which must
// be UTF-8).
std::string validUtf8(std::string_view text);

// Length of the valid UTF-8 sequence starting at text[i] (1–4), or 0 if it is not one (bad lead
// byte, missing or bad continuation bytes, an overlong form, a surrogate, past U+10FFFF).
size_t utf8Sequence(std::string_view text, size_t i);

}  // namespace rigidlab::lua
