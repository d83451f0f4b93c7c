// imgdiff: statistical comparison of a render with its reference image (see cli.h).
#include <iostream>

#include "cli.h"

int main(int argc, char** argv) {
    return rs::RunImgdiff(std::vector<std::string>(argv + 1, argv + argc), std::cout, std::cerr);
}
