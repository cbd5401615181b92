# ctest: package_subdirectory. Configures tests/packaging/subdirectory, a parent
# project that takes spindrift in with add_subdirectory() (its CMakeLists.txt
# checks the targets it gets), and compiles the parent's program against
# spindrift::spindrift. The suite stops at the compile: linking would build the
# whole library a second time (minutes). -DLINK=ON goes on to build everything,
# link and run the program.
#   cmake -DSOURCE_DIR=<repo> -DWORK_DIR=<scratch> -DCXX=<compiler> [-DLAUNCHER=<ccache>] [-DLINK=ON]
#         -P subdirectory.cmake
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)
require_vars(subdirectory.cmake SOURCE_DIR WORK_DIR CXX)


set(build ${WORK_DIR}/subdirectory)
file(REMOVE_RECURSE ${build})
set(options -G Ninja -DCMAKE_CXX_COMPILER=${CXX} -DCMAKE_BUILD_TYPE=Release -DSPINDRIFT_SOURCE_DIR=${SOURCE_DIR})
if(LAUNCHER)
    list(APPEND options -DCMAKE_CXX_COMPILER_LAUNCHER=${LAUNCHER})
endif()
run("configuring the parent project" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/packaging/subdirectory -B ${build}
    ${options})

# The parent's compile line: spindrift's headers and C++20, none of its own flags.
file(READ ${build}/compile_commands.json commands)
string(REGEX MATCH "\"command\": \"[^\"]*main\\.cpp\\.o[^\"]*\"" consumer "${commands}")
if(NOT consumer)
    message(FATAL_ERROR "no compile command for the parent's main.cpp in compile_commands.json")
endif()
if(NOT consumer MATCHES "-I${SOURCE_DIR}/include" OR NOT consumer MATCHES "-std=(gnu|c)\\+\\+20")
    message(FATAL_ERROR "the parent's program lacks spindrift's include directory or C++20: ${consumer}")
endif()
if(consumer MATCHES "-ffp-contract|-fsanitize|-fno-math-errno")
    message(FATAL_ERROR "spindrift's own compile flags reached the parent's program: ${consumer}")
endif()

if(LINK)
    run("building the parent project" ${CMAKE_COMMAND} --build ${build})
    run("running the parent's program" ${build}/consumer)
    message(STATUS "${output}")
else()
    run("compiling the parent's program" ${CMAKE_COMMAND} --build ${build} --target CMakeFiles/consumer.dir/main.cpp.o)
endif()
