# Precompiled headers: build speed only (docs/reliability.md "CI time").
#
# Each target precompiles the third-party and standard headers that most of its own sources
# already include, so each of its translation units stops parsing them again: about 1 s of CPU for
# the standard headers below and 1 s for gtest.h, per translation unit, measured with g++ 12 and
# clang 14. A header goes into a target's list only when most of that target's sources include it:
# a precompiled header is loaded into every source of the target, so OpenVDB (about 4 s to parse,
# included by 2 of sim's 24 sources), OpenImageIO and nlohmann/json stay out where few use them.
# Nothing here adds an include edge between modules: every list names only what the target's own
# sources include (tests/CheckBoundaries.cmake reads the sources, not this file), and each
# source still includes what it uses, so GALE_PCH=OFF builds the same program.
#
# ccache: a precompiled header is hashed like any include, but ccache refuses it unless told that
# the build is deterministic about it (ccache manual, "Precompiled headers"), so when the launcher
# is ccache, it runs with CCACHE_SLOPPINESS set (below) and dev builds keep hitting the cache.
option(GALE_PCH "Precompile the heavy standard and third-party headers per target" ON)

# The standard headers that at least a quarter of the sources include (grep of #include <...>).
set(GALE_PCH_STD
    <algorithm> <array> <chrono> <cmath> <cstdint> <cstdio> <cstring> <filesystem>
    <functional> <map> <memory> <optional> <sstream> <stdexcept> <string> <vector>)

# gale_precompile(TARGET [HEADER...]): the standard headers above plus HEADERs (C++ targets only).
function(gale_precompile target)
    if(NOT GALE_PCH)
        return()
    endif()
    set(headers ${GALE_PCH_STD} ${ARGN})
    target_precompile_headers(${target} PRIVATE ${headers})
endfunction()

# ccache and precompiled headers (ccache 4.7 manual): pch_defines and time_macros let it cache a
# source compiled with one; include_file_mtime/ctime let it cache the source right after the .gch
# was rebuilt. This replaces any sloppiness in ccache.conf for gale's compiles.
foreach(lang C CXX)
    if(GALE_PCH AND CMAKE_${lang}_COMPILER_LAUNCHER MATCHES "ccache$")
        set(CMAKE_${lang}_COMPILER_LAUNCHER
            ${CMAKE_COMMAND} -E env
            CCACHE_SLOPPINESS=pch_defines,time_macros,include_file_mtime,include_file_ctime
            ${CMAKE_${lang}_COMPILER_LAUNCHER})
    endif()
endforeach()
