# ctest's installed_library_consumer: installs the built library into a scratch prefix, builds
# examples/cpp (a C++-only project: LANGUAGES CXX) against it with find_package(graspmix), runs cloud_info on the
# bundled mug (its point count must be the file's POINTS) and synthesize_grasps on the demonstration and mug.
# Arguments: -DBUILD_DIR (graspmix's build tree), -DSOURCE_DIR (its source tree), -DWORK_DIR (scratch).
file(REMOVE_RECURSE ${WORK_DIR})
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message(STATUS "${what}:\n${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
run_step("install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${WORK_DIR}/prefix --component dev)
if(EXISTS ${WORK_DIR}/prefix/include/graspmix/grasp/synthesis.hpp AND EXISTS ${WORK_DIR}/prefix/lib/cmake/graspmix/graspmixConfig.cmake)
  message(STATUS "headers and graspmixConfig.cmake installed")
else()
  message(FATAL_ERROR "the install lacks the headers or graspmixConfig.cmake")
endif()
run_step("configure" ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples/cpp -B ${WORK_DIR}/build
         -DCMAKE_PREFIX_PATH=${WORK_DIR}/prefix -DCMAKE_BUILD_TYPE=Release)
run_step("build" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
# What a C++-only program needs: no C compiler (PCL's pcl_io, through VTK, once required MPI C).
file(STRINGS ${WORK_DIR}/build/CMakeCache.txt c_compiler REGEX "^CMAKE_C_COMPILER:")
if(c_compiler)
  message(FATAL_ERROR "the consumer enabled C (${c_compiler}): examples/cpp is LANGUAGES CXX")
endif()
file(STRINGS ${SOURCE_DIR}/data/mug.pcd points_line REGEX "^POINTS " LIMIT_COUNT 1)
string(REPLACE "POINTS " "" mug_points "${points_line}")
run_step("cloud_info" ${WORK_DIR}/build/cloud_info ${SOURCE_DIR}/data/mug.pcd)
if(NOT last_output MATCHES "mug.pcd: ${mug_points} points \\(${mug_points} x 1, pcd ")
  message(FATAL_ERROR "cloud_info did not print the mug's ${mug_points} points")
endif()
run_step("run" ${WORK_DIR}/build/synthesize_grasps ${SOURCE_DIR}/data/hands/wsg50.urdf ${SOURCE_DIR}/data/demos/box.pcd
         "0,0,0.2185,1,0,0,0" "finger_left_joint=0.05:0.0308" ${SOURCE_DIR}/data/mug.pcd)
if(NOT last_output MATCHES "grasp 1: log L")
  message(FATAL_ERROR "the program printed no grasp")
endif()
