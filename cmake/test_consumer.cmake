# ctest's installed_library_consumer: installs the built library into a scratch prefix, builds
# examples/cpp against it with find_package(graspmix) and runs it on the bundled demonstration and mug.
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
run_step("run" ${WORK_DIR}/build/synthesize_grasps ${SOURCE_DIR}/data/hands/wsg50.urdf ${SOURCE_DIR}/data/demos/box.pcd
         "0,0,0.2185,1,0,0,0" "finger_left_joint=0.05:0.0308" ${SOURCE_DIR}/data/mug.pcd)
if(NOT last_output MATCHES "grasp 1: log L")
  message(FATAL_ERROR "the program printed no grasp")
endif()
