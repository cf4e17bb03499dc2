# The module boundaries (docs/architecture.md), one rule per arrow that must not exist:
#   base/       no project header but its own
#   sim/        no GL, GLFW, GLM, OpenImageIO; no coupling/, render/ or app/ header
#   render/     no OpenVDB; no sim/, coupling/ or app/ header
#   coupling/   no app/ header
#   app/io/     no other app/ header
#   app/scene/  no app/bench/ header and none of the verbs' (app/*.h)
#   app/bench/  no app/scene/ header and none of the verbs'
#   validation/ sim/ and base/ only: no GL, GLFW, GLM, OpenImageIO; no coupling/, render/, app/
# and the tests, each module's tests including only what that module may include, plus the
# oracles of validation/ for the modules above which validation/ sits (sim/, coupling/):
#   tests/sim/         no coupling/, render/ or app/ header (validation/ allowed: its oracles)
#   tests/render/      no OpenVDB; no sim/, coupling/, validation/ or app/ header
#   tests/coupling/    no app/ header
#   tests/validation/  no coupling/, render/ or app/ header
# tests/app, tests/reliability and tests/fuzz test the program and may include all of it.
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

check(base "base/*.[ch]*" "sim/|render/|coupling/|app/")
check(sim "sim/*.[ch]*" "GL/|GLFW/|glm/|OpenImageIO/|EGL/|coupling/|render/|app/")
check(render "render/*.[ch]*" "openvdb/|nanovdb/|sim/|coupling/|app/")
check(coupling "coupling/*.[ch]*" "app/")
check(app_io "app/io/*.[ch]*" "app/(scene|bench)/|app/[A-Za-z]+\\.h")
check(app_scene "app/scene/*.[ch]*" "app/bench/|app/[A-Za-z]+\\.h")
check(app_bench "app/bench/*.[ch]*" "app/scene/|app/[A-Za-z]+\\.h")
check(validation "validation/*.[ch]*"
      "GL/|GLFW/|glm/|OpenImageIO/|EGL/|coupling/|render/|app/")
check(tests_sim "tests/sim/*.[ch]*" "coupling/|render/|app/")
check(tests_render "tests/render/*.[ch]*" "openvdb/|nanovdb/|sim/|coupling/|validation/|app/")
check(tests_coupling "tests/coupling/*.[ch]*" "app/")
check(tests_validation "tests/validation/*.[ch]*" "coupling/|render/|app/")

if(violations)
    string(REPLACE ";" "\n  " text "${violations}")
    message(FATAL_ERROR "module boundary crossed:\n  ${text}")
endif()
string(REPLACE ";" ", " text "${counts}")
message(STATUS "module boundaries hold (files: ${text})")
