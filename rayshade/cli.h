// The command line of spec §4. Options given here set the matching `...Set` flags so the
// scene keyword is ignored afterwards (spec §3.1).
#pragma once

#include <string>
#include <vector>

#include "libobj/implicit/implicit_overrides.h"
#include "libshade/scene.h"

namespace rs {

struct CommandLine {
    RenderOptions options;
    std::string inputFile;  // empty: standard input
    bool useCpp = true;
    std::string cppArgs;    // -P's single argument
    bool alpha = false;     // -a: write RGBA PNG
    double eyeSep = -1;     // -E (applies when options.eyeSepSet)
    bool help = false;      // -h
    bool resume = false;    // -c
    // -M method, -I tolerance, -K octree depth, -J Dratio, -B march step, -H NAME=on|off:
    // applied to every implicit object after parsing (docs/options.md).
    ImplicitOverrides implicit;
};

// Parses argv. Returns false with `error` set on a usage error (unknown option, missing
// or malformed argument, two input files); the caller prints usage and exits 1.
bool ParseCommandLine(const std::vector<std::string>& args, CommandLine& out, std::string& error);

// The usage text printed by -h and on usage errors: every option, grouped as in
// docs/options.md.
const char* UsageText();

// How many words follow option -`letter` (-R: 2, -n: 0); -1 for a letter that is not an
// option. From the same table as UsageText.
int OptionArgumentCount(char letter);

}  // namespace rs
