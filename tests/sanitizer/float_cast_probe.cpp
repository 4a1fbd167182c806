// Casts its argument, read as a double, to long and prints the result. Run under the
// sanitizer build's flags with 1e300 it must be stopped by UBSan's float-cast-overflow check
// before it prints; with 42 it prints "cast: 42" (the control).

#include <cstdio>
#include <cstdlib>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const double value = std::strtod(argv[1], nullptr);  // not a constant: nothing to fold
  const long cast = static_cast<long>(value);
  std::printf("cast: %ld\n", cast);
  return 0;
}
