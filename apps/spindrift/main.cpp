// Placeholder: the command line tool is being written (see issue 2).
#include <spindrift/world.h>

#include <cstdio>

int main() {
    std::printf("spindrift %s\n", spindrift::versionString());
    return 0;
}
