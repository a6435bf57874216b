# seam_module(NAME DEPS ...): one folder src/seam/NAME = one namespace = one library seam_NAME.
# Sources are globbed so that adding a file needs no CMake edit.
function(seam_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS;PRIVATE_INCLUDES" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/src/seam/${name}/*.cpp)
  if(sources)
    add_library(seam_${name} STATIC ${sources})
    target_include_directories(seam_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
    target_include_directories(seam_${name} SYSTEM PRIVATE ${ARG_PRIVATE_INCLUDES})
    target_link_libraries(seam_${name} PUBLIC ${ARG_DEPS} PRIVATE seam_warnings ${ARG_PRIVATE_DEPS})
  else()
    add_library(seam_${name} INTERFACE)
    target_include_directories(seam_${name} INTERFACE ${PROJECT_SOURCE_DIR}/src)
    target_link_libraries(seam_${name} INTERFACE ${ARG_DEPS})
  endif()
endfunction()

# seam_unit_test(MODULE DEPS ... [MPI_RANKS n ...]): tests/unit/MODULE/*.cpp -> one GoogleTest
# executable unit_MODULE. With MPI_RANKS the executable has a main() that initializes MPI (the
# directory's main.cpp, or else tests/unit/mpi_main.cpp) and also runs under mpiexec on each
# number of ranks given.
function(seam_unit_test name)
  cmake_parse_arguments(ARG "" "" "DEPS;MPI_RANKS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/tests/unit/${name}/*.cpp)
  if(NOT sources)
    return()
  endif()
  # Without a main() of its own, an MPI test directory takes tests/unit/mpi_main.cpp.
  if(ARG_MPI_RANKS AND NOT EXISTS ${PROJECT_SOURCE_DIR}/tests/unit/${name}/main.cpp)
    list(APPEND sources ${PROJECT_SOURCE_DIR}/tests/unit/mpi_main.cpp)
  endif()
  add_executable(unit_${name} ${sources})
  if(ARG_MPI_RANKS)
    target_link_libraries(unit_${name} PRIVATE seam_${name} ${ARG_DEPS} GTest::gtest seam_warnings)
  else()
    target_link_libraries(unit_${name} PRIVATE seam_${name} ${ARG_DEPS} GTest::gtest GTest::gtest_main seam_warnings)
  endif()
  target_include_directories(unit_${name} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  add_test(NAME unit_${name} COMMAND unit_${name} --gtest_brief=1 WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}/tests)
  set_tests_properties(unit_${name} PROPERTIES LABELS unit)
  # The instrumented build (make sanitize) runs the MPI cases 10 to 20 times slower.
  set(mpi_timeout 300)
  if(SEAM_SANITIZE)
    set(mpi_timeout 1800)
  endif()
  foreach(np ${ARG_MPI_RANKS})
    add_test(NAME unit_${name}_np${np}
             COMMAND ${MPIEXEC_EXECUTABLE} ${MPIEXEC_NUMPROC_FLAG} ${np} --oversubscribe
                     $<TARGET_FILE:unit_${name}> --gtest_brief=1
             WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}/tests)
    set_tests_properties(unit_${name}_np${np} PROPERTIES LABELS "unit;mpi" PROCESSORS ${np} TIMEOUT ${mpi_timeout}
      ENVIRONMENT "OMPI_ALLOW_RUN_AS_ROOT=1;OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1;OMPI_MCA_rmaps_base_oversubscribe=1")
  endforeach()
endfunction()
