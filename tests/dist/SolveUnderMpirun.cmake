# `mpirun -n 2 gale solve` as users meet it (ctest DistributedSolve.UnderMpirun, label mpi):
#   - the scene's field and report are written once, by rank 0, atomically: both files exist, no
#     temporary is left in the folder, and the report's solver figures (iterations, levels,
#     converged) equal a one-process run's;
#   - a bad scene ends every rank with the one-process exit code (2) and one error line, and
#     writes nothing.
# Inputs: GALE (the program), MPIEXEC, SOURCE_DIR, WORK (an empty scratch folder).
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(scene ${SOURCE_DIR}/examples/lee_ridge_mass_consistent.toml)

execute_process(COMMAND ${GALE} solve ${scene} -o ${WORK}/one.vdb --report ${WORK}/one.json
                RESULT_VARIABLE rc1 OUTPUT_QUIET ERROR_VARIABLE err1)
execute_process(COMMAND ${MPIEXEC} --oversubscribe -n 2 ${GALE} solve ${scene}
                        -o ${WORK}/two.vdb --report ${WORK}/two.json
                RESULT_VARIABLE rc2 OUTPUT_VARIABLE out2 ERROR_VARIABLE err2)
if(NOT rc1 EQUAL 0 OR NOT rc2 EQUAL 0)
    message(FATAL_ERROR "exit codes: one process ${rc1}, two ranks ${rc2}\n${err1}\n${err2}")
endif()
foreach(f one.vdb one.json two.vdb two.json)
    if(NOT EXISTS ${WORK}/${f})
        message(FATAL_ERROR "${f} was not written")
    endif()
endforeach()
file(GLOB temporaries ${WORK}/.*tmp*)
if(temporaries)
    message(FATAL_ERROR "temporaries left behind: ${temporaries}")
endif()
file(READ ${WORK}/one.json one)
file(READ ${WORK}/two.json two)
foreach(key iterations levels converged)
    string(REGEX MATCH "\"${key}\": *[^,}\n]+" a "${one}")
    string(REGEX MATCH "\"${key}\": *[^,}\n]+" b "${two}")
    if(a STREQUAL "" OR NOT a STREQUAL b)
        message(FATAL_ERROR "report ${key}: one process '${a}', two ranks '${b}'")
    endif()
endforeach()

# A bad scene: exit 2 from mpirun, one error line, nothing written.
execute_process(COMMAND ${MPIEXEC} --oversubscribe -n 2 ${GALE} solve
                        ${SOURCE_DIR}/tests/data/bad/control_chars_in_kind.toml -o ${WORK}/bad.vdb
                RESULT_VARIABLE rc3 OUTPUT_QUIET ERROR_VARIABLE err3)
if(NOT rc3 EQUAL 2)
    message(FATAL_ERROR "bad scene under mpirun: exit ${rc3}, expected 2\n${err3}")
endif()
string(REGEX MATCHALL "gale: error:" lines "${err3}")
list(LENGTH lines n)
if(NOT n EQUAL 1)
    message(FATAL_ERROR "bad scene under mpirun: ${n} error lines, expected 1:\n${err3}")
endif()
if(EXISTS ${WORK}/bad.vdb)
    message(FATAL_ERROR "bad scene under mpirun wrote bad.vdb")
endif()
