#include "cli.hpp"

int main(int argc, char** argv) {
  return omninav::cli::run(argc, argv);
}
