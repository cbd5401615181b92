# Include-direction check (ctest: include_direction), run as
#   cmake -DSOURCE_DIR=<repo> -P cmake/check_includes.cmake
# Every folder of src/ has a rank; a file may include its own folder and
# folders of a lower rank, never one of the same rank (peers stay independent)
# or a higher one. docs/design.md ("Folders") says why the order is this one.
# Fails with one line per wrong include: file:line: folder -> folder.

# Lowest first. Folders on one line share a rank and may not include each other.
set(RANK_core 0)
set(RANK_kernels 1)
set(RANK_particles 2)   # the emitter model both backends share
set(RANK_effects 3)     # CPU backend
set(RANK_gpu 3)         # Vulkan backend
set(RANK_fluid 3)       # constraint fluid solver, with its body proxy
set(RANK_coupling 4)    # Box2D: fills the fluid's body proxy, hands impulses back
set(RANK_world 5)       # the hub: struct World, stepWorld, the public API
set(RANK_render 6)      # draws a world
set(RANK_scene 7)       # scene files -> public API
set(RANK_io 7)          # caches, summaries, video: public API only
set(FOLDERS core kernels particles effects gpu fluid coupling world render scene io)

if(NOT SOURCE_DIR)
    message(FATAL_ERROR "check_includes.cmake: pass -DSOURCE_DIR=<repository root>")
endif()

file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR}/src
     ${SOURCE_DIR}/src/*.h ${SOURCE_DIR}/src/*.cpp ${SOURCE_DIR}/src/*.glsl ${SOURCE_DIR}/src/*.comp
     ${SOURCE_DIR}/src/*.vert ${SOURCE_DIR}/src/*.frag)
set(errors 0)
foreach(file ${files})
    string(REGEX MATCH "^[^/]+" folder ${file})
    if(NOT DEFINED RANK_${folder})
        message(NOTICE "src/${file}: folder '${folder}' has no rank in cmake/check_includes.cmake")
        math(EXPR errors "${errors} + 1")
        continue()
    endif()
    file(STRINGS ${SOURCE_DIR}/src/${file} lines)
    set(number 0)
    foreach(line IN LISTS lines)
        math(EXPR number "${number} + 1")
        # Quoted includes name a folder of src/ first ("gpu/gpu_world.h"); a bare
        # name ("types.glsl") is a shader include resolved by glslc -I, checked
        # by glslc itself.
        if(line MATCHES "^[ \t]*#[ \t]*include[ \t]+\"([^/\"]+)/[^\"]+\"")
            set(target ${CMAKE_MATCH_1})
            if(target STREQUAL folder)
                continue()
            endif()
            if(NOT DEFINED RANK_${target})
                message(NOTICE "src/${file}:${number}: includes unknown folder '${target}'")
                math(EXPR errors "${errors} + 1")
            elseif(NOT RANK_${target} LESS RANK_${folder})
                message(NOTICE "src/${file}:${number}: ${folder} (rank ${RANK_${folder}}) must not include "
                                   "${target} (rank ${RANK_${target}}): ${line}")
                math(EXPR errors "${errors} + 1")
            endif()
        endif()
    endforeach()
endforeach()
if(errors GREATER 0)
    message(FATAL_ERROR "${errors} include(s) point up or sideways; see docs/design.md, \"Folders\"")
endif()
list(LENGTH files count)
message(STATUS "include direction: ${count} files of src/ checked")
