// A small PNG inspector for the sandbox's picture tests (reads with Debian's libstb stb_image).
//
//   png_check pixel IMAGE X Y                 prints "R G B" of the pixel (X right, Y down, from 0)
//   png_check near IMAGE X Y R G B TOL        exit 0 if every channel is within TOL, else 1
//   png_check diff A B X0 Y0 X1 Y1            prints how many pixels of the rectangle differ
//   png_check count IMAGE X0 Y0 X1 Y1 R G B TOL
//                                             prints how many pixels of the rectangle (clipped to
//                                             the image) are within TOL of R G B in every channel
//   png_check size IMAGE                      prints "W H"
#include <stb_image.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace {

struct Image {
  int w = 0, h = 0;
  std::unique_ptr<unsigned char, void (*)(void*)> data{nullptr, stbi_image_free};
  const unsigned char* at(int x, int y) const { return data.get() + (static_cast<size_t>(y) * w + x) * 3; }
};

Image load(const char* file) {
  Image img;
  int channels = 0;
  img.data.reset(stbi_load(file, &img.w, &img.h, &channels, 3));
  if (!img.data) {
    std::fprintf(stderr, "png_check: cannot read %s: %s\n", file, stbi_failure_reason());
    std::exit(2);
  }
  return img;
}

int number(const char* s) { return std::atoi(s); }

void requireInside(const Image& img, int x, int y) {
  if (x < 0 || y < 0 || x >= img.w || y >= img.h) {
    std::fprintf(stderr, "png_check: (%d, %d) is outside the %dx%d image\n", x, y, img.w, img.h);
    std::exit(2);
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  if (cmd == "pixel" && argc == 5) {
    const Image img = load(argv[2]);
    const int x = number(argv[3]), y = number(argv[4]);
    requireInside(img, x, y);
    const unsigned char* p = img.at(x, y);
    std::printf("%d %d %d\n", p[0], p[1], p[2]);
    return 0;
  }
  if (cmd == "near" && argc == 9) {
    const Image img = load(argv[2]);
    const int x = number(argv[3]), y = number(argv[4]), tol = number(argv[8]);
    requireInside(img, x, y);
    const unsigned char* p = img.at(x, y);
    const int want[3] = {number(argv[5]), number(argv[6]), number(argv[7])};
    for (int c = 0; c < 3; ++c) {
      if (std::abs(p[c] - want[c]) > tol) {
        std::printf("pixel (%d, %d) is %d %d %d, expected %d %d %d ± %d\n", x, y, p[0], p[1], p[2], want[0], want[1],
                    want[2], tol);
        return 1;
      }
    }
    return 0;
  }
  if (cmd == "diff" && argc == 8) {
    const Image a = load(argv[2]), b = load(argv[3]);
    if (a.w != b.w || a.h != b.h) {
      std::printf("%d\n", a.w * a.h);
      return 0;
    }
    const int x0 = number(argv[4]), y0 = number(argv[5]), x1 = number(argv[6]), y1 = number(argv[7]);
    requireInside(a, x0, y0);
    requireInside(a, x1 - 1, y1 - 1);
    long count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c)
          if (a.at(x, y)[c] != b.at(x, y)[c]) {
            ++count;
            break;
          }
    std::printf("%ld\n", count);
    return 0;
  }
  if (cmd == "count" && argc == 11) {
    const Image img = load(argv[2]);
    const int x0 = std::max(0, number(argv[3])), y0 = std::max(0, number(argv[4]));
    const int x1 = std::min(img.w, number(argv[5])), y1 = std::min(img.h, number(argv[6]));
    const int want[3] = {number(argv[7]), number(argv[8]), number(argv[9])}, tol = number(argv[10]);
    long count = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        const unsigned char* p = img.at(x, y);
        if (std::abs(p[0] - want[0]) <= tol && std::abs(p[1] - want[1]) <= tol && std::abs(p[2] - want[2]) <= tol) ++count;
      }
    std::printf("%ld\n", count);
    return 0;
  }
  if (cmd == "size" && argc == 3) {
    const Image img = load(argv[2]);
    std::printf("%d %d\n", img.w, img.h);
    return 0;
  }
  std::fprintf(stderr, "usage: png_check pixel IMAGE X Y | near IMAGE X Y R G B TOL | diff A B X0 Y0 X1 Y1 | "
                       "count IMAGE X0 Y0 X1 Y1 R G B TOL | size IMAGE\n");
  return 2;
}
