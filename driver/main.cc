// gearkit: one executable, one scene file. See `gearkit --help`.
#include "driver.h"

#include <iostream>

int
main(int argc, char **argv)
{
  return gearkit::gearkit_main(std::vector<std::string>(argv + 1, argv + argc), std::cout,
                               std::cerr);
}
