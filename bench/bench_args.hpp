// The command lines of the bench programs: --help (or -h) prints the usage and exits 0; an
// argument the program does not take, or a count that is no positive integer, names itself and
// the usage on stderr and exits 2 - never a run with a count of 0 (rows of NaN).
#pragma once
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace footpoint::bench {

[[noreturn]] inline void exit_with_usage(const char* usage, int code) {
  std::fputs(usage, code == 0 ? stdout : stderr);
  std::exit(code);
}

[[noreturn]] inline void refuse_argument(const char* program, const char* what, const char* arg,
                                         const char* usage) {
  std::fprintf(stderr, "%s: %s '%s'\n", program, what, arg);
  exit_with_usage(usage, 2);
}

// Exits 0 after the usage when an argument asks for help.
inline void exit_on_help(int argc, char** argv, const char* usage) {
  for (int i = 1; i < argc; ++i)
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) exit_with_usage(usage, 0);
}

// A program that takes no argument but --help.
inline void take_no_arguments(int argc, char** argv, const char* usage) {
  exit_on_help(argc, argv, usage);
  if (argc > 1) refuse_argument(argv[0], "unexpected argument", argv[1], usage);
}

// A count: a positive integer up to 10^9.
inline long count_argument(const char* program, const char* text, const char* usage) {
  char* end = nullptr;
  const long value = std::strtol(text, &end, 10);
  if (end == text || *end != '\0' || value <= 0 || value > 1000000000)
    refuse_argument(program, "not a positive count:", text, usage);
  return value;
}

}  // namespace footpoint::bench
