# ctest: package_pkg_config. Compiles examples/particle_effect with nothing but
# the flags `pkg-config` gives for the installed spindrift.pc (--static for a
# static library), runs it and checks its summary line.
#   cmake -DSOURCE_DIR=<repo> -DPREFIX=<installed> -DLIBDIR=<lib dir> -DWORK_DIR=<scratch>
#         -DCXX=<compiler> -P pkg_config.cmake
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)
require_vars(pkg_config.cmake SOURCE_DIR PREFIX LIBDIR WORK_DIR CXX)
find_program(PKG_CONFIG pkg-config REQUIRED)

set(ENV{PKG_CONFIG_PATH} ${PREFIX}/${LIBDIR}/pkgconfig)
set(static "")
if(EXISTS ${PREFIX}/${LIBDIR}/libspindrift.a)
    set(static --static)
endif()
execute_process(COMMAND ${PKG_CONFIG} ${static} --cflags --libs spindrift
                RESULT_VARIABLE rc OUTPUT_VARIABLE flags ERROR_VARIABLE err OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "pkg-config ${static} --cflags --libs spindrift failed:\n${err}")
endif()
message(STATUS "pkg-config ${static}: ${flags}")
separate_arguments(flags UNIX_COMMAND "${flags}")

set(program ${WORK_DIR}/pkg_config_particle_effect)
file(MAKE_DIRECTORY ${WORK_DIR})
execute_process(COMMAND ${CXX} -std=c++20 -O1 ${SOURCE_DIR}/examples/particle_effect/main.cpp -o ${program} ${flags}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "compiling with pkg-config's flags failed:\n${out}")
endif()
if(NOT static)
    set(ENV{LD_LIBRARY_PATH} ${PREFIX}/${LIBDIR})  # pkg-config gives no run path
endif()
execute_process(COMMAND ${program} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0 OR NOT out MATCHES "particles=[1-9][0-9]* collisions=[1-9]")
    message(FATAL_ERROR "the program built with pkg-config's flags failed (${rc}):\n${out}")
endif()
message(STATUS "${out}")
