// Back buffer → PNG with stb_image_write (Debian's libstb; screenshot.h).
#include "screenshot.h"

#include <stb_image_write.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <system_error>
#include <vector>

#include "gl.h"

namespace rigidlab::sandbox {

bool writeScreenshot(const std::filesystem::path& file, int width, int height, std::string& error) {
  if (width <= 0 || height <= 0) {
    error = "empty window";
    return false;
  }
  std::vector<unsigned char> pixels(static_cast<size_t>(width) * height * 3);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadBuffer(GL_BACK);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  if (const GLenum e = glGetError(); e != GL_NO_ERROR) {
    error = "glReadPixels failed (GL error " + std::to_string(e) + ")";
    return false;
  }
  // GL's rows go bottom-up, PNG's top-down.
  const size_t row = static_cast<size_t>(width) * 3;
  std::vector<unsigned char> flipped(pixels.size());
  for (int y = 0; y < height; ++y)
    std::memcpy(&flipped[static_cast<size_t>(y) * row], &pixels[static_cast<size_t>(height - 1 - y) * row], row);

  const std::filesystem::path temporary = file.string() + ".partial-" + std::to_string(::getpid());
  if (!stbi_write_png(temporary.c_str(), width, height, 3, flipped.data(), static_cast<int>(row))) {
    error = file.string() + ": cannot write the PNG";
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    return false;
  }
  std::error_code ec;
  std::filesystem::rename(temporary, file, ec);
  if (ec) {
    error = file.string() + ": " + ec.message();
    std::filesystem::remove(temporary, ec);
    return false;
  }
  return true;
}

}  // namespace rigidlab::sandbox
