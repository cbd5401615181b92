# ctest: package_install (fixture spindrift_package). Installs the build tree
# into a fresh prefix, as a user or a packager would, and checks what arrived:
# the public headers exactly (nothing of src/), the library, the CMake package
# and the pkg-config file, and the tool, which must run. A shared library must
# export no internal namespace.
#   cmake -DBUILD_DIR=<build> -DSOURCE_DIR=<repo> -DPREFIX=<dir> -DLIBDIR=<lib dir>
#         -DVERSION=<x.y.z> [-DTOOL=ON] -P install_package.cmake
include(${CMAKE_CURRENT_LIST_DIR}/common.cmake)
require_vars(install_package.cmake BUILD_DIR SOURCE_DIR PREFIX LIBDIR VERSION)

file(REMOVE_RECURSE ${PREFIX})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${PREFIX}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cmake --install failed (${rc}):\n${out}")
endif()

set(errors "")
# Headers: exactly include/spindrift/*.h and the generated version.h.
file(GLOB source_headers RELATIVE ${SOURCE_DIR}/include/spindrift ${SOURCE_DIR}/include/spindrift/*.h)
list(APPEND source_headers version.h)
list(SORT source_headers)
file(GLOB_RECURSE installed_headers RELATIVE ${PREFIX}/include ${PREFIX}/include/*)
list(TRANSFORM installed_headers REPLACE "^spindrift/" "")
list(SORT installed_headers)
if(NOT installed_headers STREQUAL source_headers)
    string(APPEND errors "installed headers [${installed_headers}] are not the public ones [${source_headers}]\n")
endif()

foreach(file ${LIBDIR}/cmake/spindrift/spindriftConfig.cmake ${LIBDIR}/cmake/spindrift/spindriftConfigVersion.cmake
             ${LIBDIR}/cmake/spindrift/spindriftTargets.cmake ${LIBDIR}/pkgconfig/spindrift.pc)
    if(NOT EXISTS ${PREFIX}/${file})
        string(APPEND errors "missing ${file}\n")
    endif()
endforeach()
file(GLOB libraries ${PREFIX}/${LIBDIR}/libspindrift.a ${PREFIX}/${LIBDIR}/libspindrift.so)
list(LENGTH libraries count)
if(NOT count EQUAL 1)
    string(APPEND errors "expected one of libspindrift.a or libspindrift.so in ${LIBDIR}, found [${libraries}]\n")
endif()

# A shared library exports the public API and nothing of the internal namespaces.
if(EXISTS ${PREFIX}/${LIBDIR}/libspindrift.so)
    execute_process(COMMAND nm -D -C --defined-only ${PREFIX}/${LIBDIR}/libspindrift.so
                    RESULT_VARIABLE rc OUTPUT_VARIABLE symbols ERROR_VARIABLE err)
    if(NOT rc EQUAL 0)
        string(APPEND errors "nm failed: ${err}\n")
    endif()
    foreach(public "spindrift::createWorld(" "spindrift::loadScene(" "spindrift::renderFrame(" "typeinfo for spindrift::Error")
        string(FIND "${symbols}" "${public}" at)
        if(at EQUAL -1)
            string(APPEND errors "libspindrift.so does not export ${public}\n")
        endif()
    endforeach()
    string(REGEX MATCHALL "spindrift::(core|kernels|particles|effects|gpu|fluid|coupling|world|render|scene|io)::[^\n]*"
           internal "${symbols}")
    if(internal)
        list(LENGTH internal n)
        list(SUBLIST internal 0 5 some)
        string(APPEND errors "libspindrift.so exports ${n} internal symbols, e.g. ${some}\n")
    endif()
endif()

if(TOOL)
    execute_process(COMMAND ${PREFIX}/bin/spindrift --version RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    if(NOT rc EQUAL 0 OR NOT out MATCHES "${VERSION}")
        string(APPEND errors "installed tool: `spindrift --version` gave ${rc}: ${out}\n")
    endif()
endif()

if(errors)
    message(FATAL_ERROR "installed package in ${PREFIX}:\n${errors}")
endif()
message(STATUS "installed and checked: ${PREFIX}")
