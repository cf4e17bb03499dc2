# The module boundaries (docs/architecture.md), one rule per arrow that must not exist:
#   base/       no project header but its own
#   sim/        no GL, GLFW, GLM, OpenImageIO; no coupling/, render/ or app/ header
#   render/     no OpenVDB; no sim/, coupling/ or app/ header
#   coupling/   no app/ header
#   app/io/     no other app/ header
#   app/scene/  no app/bench/ header and none of the verbs' (app/*.h)
#   app/bench/  no app/scene/ header and none of the verbs'
#   validation/ sim/ and base/ only: no GL, GLFW, GLM, OpenImageIO; no coupling/, render/, app/
#   dist/       sim/ and base/ only (and of sim's internal headers only PoissonDetail.h, whose
#               kernels it runs on each rank's subdomain); base/, sim/, render/, validation/ never
#               include dist/
# and the tests, each module's tests including only what that module may include, plus the
# oracles of validation/ for the modules above which validation/ sits (sim/, coupling/):
#   tests/sim/         no coupling/, render/ or app/ header (validation/ allowed: its oracles)
#   tests/render/      no OpenVDB; no sim/, coupling/, validation/ or app/ header
#   tests/coupling/    no app/ header
#   tests/validation/  no coupling/, render/ or app/ header
#   tests/dist/        no coupling/, render/ or app/ header
# tests/app, tests/reliability and tests/fuzz test the program and may include all of it.
#   sim/'s internal headers (a "/// \internal" line in the preamble) only in sim/ and tests/sim,
#   and docs/architecture.md's table of sim's headers says which are internal, as they do
set(violations "")
set(counts "")

# check(NAME GLOB REGEX): every file under GLOB whose include lines match REGEX is a violation.
function(check name pattern regex)
    file(GLOB_RECURSE files ${SOURCE_DIR}/${pattern})
    list(LENGTH files n)
    if(n EQUAL 0)
        message(FATAL_ERROR "boundary check found no sources for ${name} (${SOURCE_DIR}/${pattern})")
    endif()
    foreach(f IN LISTS files)
        file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"](${regex})")
        if(lines)
            list(APPEND violations "${f}: ${lines}")
        endif()
    endforeach()
    set(violations "${violations}" PARENT_SCOPE)
    list(APPEND counts "${name} ${n}")
    set(counts "${counts}" PARENT_SCOPE)
endfunction()

check(base "base/*.[ch]*" "sim/|render/|coupling/|app/|dist/")
check(sim "sim/*.[ch]*" "GL/|GLFW/|glm/|OpenImageIO/|EGL/|coupling/|render/|app/|dist/")
check(render "render/*.[ch]*" "openvdb/|nanovdb/|sim/|coupling/|app/|dist/")
check(coupling "coupling/*.[ch]*" "app/")
check(app_io "app/io/*.[ch]*" "app/(scene|bench)/|app/[A-Za-z]+\\.h")
check(app_scene "app/scene/*.[ch]*" "app/bench/|app/[A-Za-z]+\\.h")
check(app_bench "app/bench/*.[ch]*" "app/scene/|app/[A-Za-z]+\\.h")
check(validation "validation/*.[ch]*"
      "GL/|GLFW/|glm/|OpenImageIO/|EGL/|coupling/|render/|app/|dist/")
check(dist "dist/*.[ch]*" "GL/|GLFW/|glm/|OpenImageIO/|EGL/|coupling/|render/|app/|validation/")
check(tests_dist "tests/dist/*.[ch]*" "coupling/|render/|app/")
check(tests_sim "tests/sim/*.[ch]*" "coupling/|render/|app/")
check(tests_render "tests/render/*.[ch]*" "openvdb/|nanovdb/|sim/|coupling/|validation/|app/")
check(tests_coupling "tests/coupling/*.[ch]*" "app/")
check(tests_validation "tests/validation/*.[ch]*" "coupling/|render/|app/")

# sim's headers: public (any module above may include them) or internal (sim/ and its white-box
# tests only). A header says it is internal by a line starting "/// \internal"; the table in
# docs/architecture.md must list every sim/ header once with the same word.
file(GLOB sim_headers ${SOURCE_DIR}/sim/*.h)
set(sim_internal "")
set(sim_public "")
foreach(h IN LISTS sim_headers)
    get_filename_component(name ${h} NAME)
    file(STRINGS ${h} marker REGEX "^/// \\\\internal")
    if(marker)
        list(APPEND sim_internal ${name})
    else()
        list(APPEND sim_public ${name})
    endif()
endforeach()
list(LENGTH sim_internal n_internal)
list(LENGTH sim_public n_public)
if(n_internal EQUAL 0 OR n_public EQUAL 0)
    message(FATAL_ERROR "sim header check found ${n_public} public and ${n_internal} internal headers")
endif()
string(REPLACE "." "\\." internal_regex "${sim_internal}")
string(REPLACE ";" "|" internal_regex "${internal_regex}")
set(outside "")
foreach(dir app base coupling render tests validation dist)
    file(GLOB_RECURSE found ${SOURCE_DIR}/${dir}/*.h ${SOURCE_DIR}/${dir}/*.cpp)
    list(APPEND outside ${found})
endforeach()
foreach(f IN LISTS outside)
    string(FIND "${f}" "${SOURCE_DIR}/tests/sim/" white_box)
    if(white_box EQUAL 0)
        continue()
    endif()
    set(regex "${internal_regex}")
    string(FIND "${f}" "${SOURCE_DIR}/dist/" in_dist)
    if(in_dist EQUAL 0)  # dist/ runs sim's multigrid kernels: PoissonDetail.h is its one exception
        string(REPLACE "PoissonDetail\\.h" "" regex "${regex}")
        string(REPLACE "||" "|" regex "${regex}")
        string(REGEX REPLACE "^\\||\\|$" "" regex "${regex}")
    endif()
    file(STRINGS ${f} lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]sim/(${regex})[>\"]")
    if(lines)
        list(APPEND violations "${f}: ${lines} (internal to sim/)")
    endif()
endforeach()
file(STRINGS ${SOURCE_DIR}/docs/architecture.md rows REGEX "^\\| `sim/[A-Za-z]+\\.h` \\|")
foreach(kind public internal)
    foreach(name IN LISTS sim_${kind})
        set(found 0)
        foreach(row IN LISTS rows)
            if(row MATCHES "^\\| `sim/([A-Za-z]+\\.h)` \\| ([a-z]+) \\|" AND CMAKE_MATCH_1 STREQUAL name)
                math(EXPR found "${found} + 1")
                if(NOT CMAKE_MATCH_2 STREQUAL kind)
                    list(APPEND violations
                         "docs/architecture.md: sim/${name} is ${kind}, the table says ${CMAKE_MATCH_2}")
                endif()
            endif()
        endforeach()
        if(NOT found EQUAL 1)
            list(APPEND violations "docs/architecture.md: sim/${name} listed ${found} times, not once")
        endif()
    endforeach()
endforeach()
foreach(row IN LISTS rows)
    if(row MATCHES "^\\| `sim/([A-Za-z]+\\.h)` \\|" AND NOT EXISTS ${SOURCE_DIR}/sim/${CMAKE_MATCH_1})
        list(APPEND violations "docs/architecture.md: sim/${CMAKE_MATCH_1} is not a header of sim/")
    endif()
endforeach()
list(APPEND counts "sim headers ${n_public} public ${n_internal} internal")

if(violations)
    string(REPLACE ";" "\n  " text "${violations}")
    message(FATAL_ERROR "module boundary crossed:\n  ${text}")
endif()
string(REPLACE ";" ", " text "${counts}")
message(STATUS "module boundaries hold (files: ${text})")
