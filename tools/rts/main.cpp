// rts: the warpath command-line program. Each subcommand registers itself on the app
// (rts_main.cpp).

#include "rts/rts_main.h"

int main(int argc, char** argv) {
  return warpath::tools::rtsMain(argc, argv);
}
