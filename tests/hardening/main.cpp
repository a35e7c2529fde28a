// doctest main, plus the helper modes the determinism tests start as separate processes:
//   hardening_tests --state-hash SCENE STEPS   prints the scene's state hash after STEPS steps
//   hardening_tests --print-hashes             prints the golden-hash table (test_determinism.cpp)
#define DOCTEST_CONFIG_IMPLEMENT
#include <doctest/doctest.h>

#include <cstring>

// test_determinism.cpp (absent from executables without it); returns -1 for anything else.
int hardeningHelperMain(int argc, char** argv) __attribute__((weak));

int main(int argc, char** argv) {
  if (hardeningHelperMain && argc > 1 && std::strncmp(argv[1], "--", 2) == 0 && std::strncmp(argv[1], "--dt-", 5) != 0) {
    const int rc = hardeningHelperMain(argc, argv);
    if (rc >= 0) return rc;
  }
  doctest::Context context(argc, argv);
  return context.run();
}
