// Every public header, included by a program of the parent project.
#include <spindrift/bodies.h>
#include <spindrift/effects.h>
#include <spindrift/fires.h>
#include <spindrift/fluid.h>
#include <spindrift/render.h>
#include <spindrift/scene.h>
#include <spindrift/version.h>
#include <spindrift/world.h>

#include <cstdio>
#include <cstring>

int main() {
    // The library's version string and the header's macro agree.
    std::printf("spindrift %s\n", spindrift::versionString());
    return std::strcmp(spindrift::versionString(), SPINDRIFT_VERSION) == 0 ? 0 : 1;
}
