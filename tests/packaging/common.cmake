# Helpers shared by the packaging scripts (included, with include(common.cmake)).

# Fails unless every named variable was passed with -D<name>=...
function(require_vars script)
    foreach(var ${ARGN})
        if(NOT DEFINED ${var})
            message(FATAL_ERROR "${script}: pass -D${var}=...")
        endif()
    endforeach()
endfunction()

# Runs a command; fails with its output, labelled `what`, unless it exits 0.
# Leaves what it printed (stdout and stderr) in `output`.
function(run what)
    execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
    if(NOT rc EQUAL 0)
        message(FATAL_ERROR "${what} failed (${rc}):\n${out}")
    endif()
    set(output "${out}" PARENT_SCOPE)
endfunction()
