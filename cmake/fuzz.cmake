# SPDX-License-Identifier: BSD-3-Clause
# libFuzzer targets for every file loader, the configuration reader and the PointCloud2
# conversion (docs/fuzzing.md; scripts/fuzz builds and runs them). Included from CMakeLists.txt
# when FREEFORM_INSPECTION_BUILD_FUZZ is ON; meant for a build directory of its own, since it
# instruments the core library itself.
if(NOT CMAKE_CXX_COMPILER_ID MATCHES "Clang")
  message(FATAL_ERROR
    "FREEFORM_INSPECTION_BUILD_FUZZ needs clang (libFuzzer is part of clang), but the C++ "
    "compiler is ${CMAKE_CXX_COMPILER_ID} (${CMAKE_CXX_COMPILER}). Configure a fresh build "
    "directory with -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++, or use scripts/fuzz.")
endif()

# Coverage and sanitizers on every core source the targets reach; libFuzzer's main only at the
# link of the targets. UB aborts (no recovery) so that libFuzzer records it as a crash.
set(FREEFORM_FUZZ_SANITIZERS address,undefined)
set(FREEFORM_FUZZ_COMPILE_OPTIONS -fsanitize=fuzzer-no-link,${FREEFORM_FUZZ_SANITIZERS}
  -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
# clang's -Wconversion also warns on every int index into a vector, which GCC (the normal build)
# does not: noise here.
target_compile_options(freeform_inspection_core PRIVATE ${FREEFORM_FUZZ_COMPILE_OPTIONS}
  -Wno-sign-conversion)
# Anything else linking the instrumented core (tools, unit tests) needs the sanitizer runtimes.
target_link_options(freeform_inspection_core INTERFACE -fsanitize=${FREEFORM_FUZZ_SANITIZERS})

function(freeform_add_fuzz_target name)
  add_executable(fuzz_${name} test/fuzz/fuzz_${name}.cpp)
  target_compile_options(fuzz_${name} PRIVATE ${FREEFORM_FUZZ_COMPILE_OPTIONS})
  target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer,${FREEFORM_FUZZ_SANITIZERS})
  target_link_libraries(fuzz_${name} PRIVATE ${ARGN})
  add_dependencies(fuzz fuzz_${name})
endfunction()

add_custom_target(fuzz)
# PCL's PCD reader is a module the core opens at run time (src/core/io/pcd_module.cpp): built and
# instrumented with the targets, beside them.
target_compile_options(freeform_inspection_pcd PRIVATE ${FREEFORM_FUZZ_COMPILE_OPTIONS}
  -Wno-sign-conversion)
add_dependencies(fuzz freeform_inspection_pcd)

# The entries shared with test/unit/fuzz_corpus_test.cpp.
add_library(freeform_fuzz_entries STATIC test/fuzz/fuzz_entries.cpp test/fuzz/fuzz_input_file.cpp)
target_compile_options(freeform_fuzz_entries PRIVATE ${FREEFORM_FUZZ_COMPILE_OPTIONS})
target_include_directories(freeform_fuzz_entries PUBLIC test/fuzz)
target_include_directories(freeform_fuzz_entries SYSTEM PRIVATE ${PCL_INCLUDE_DIRS})
target_link_libraries(freeform_fuzz_entries PUBLIC freeform_inspection_core ${PCL_LIBRARIES})
foreach(target stl ply_mesh ply_scan obj pcd config_yaml)
  freeform_add_fuzz_target(${target} freeform_fuzz_entries)
endforeach()

# PointCloud2: only the message headers and the serialization libraries, not catkin or the
# package's generated messages, so this target builds with FREEFORM_INSPECTION_BUILD_ROS=OFF too.
find_path(FREEFORM_FUZZ_ROS_INCLUDE_DIR sensor_msgs/PointCloud2.h
  HINTS ${catkin_INCLUDE_DIRS} PATHS /opt/ros/noetic/include)
foreach(lib roscpp_serialization rostime cpp_common)
  find_library(FREEFORM_FUZZ_${lib}_LIBRARY ${lib} PATHS /opt/ros/noetic/lib)
  list(APPEND FREEFORM_FUZZ_ROS_LIBRARIES ${FREEFORM_FUZZ_${lib}_LIBRARY})
endforeach()
if(FREEFORM_FUZZ_ROS_INCLUDE_DIR AND NOT FREEFORM_FUZZ_ROS_LIBRARIES MATCHES "NOTFOUND")
  add_library(freeform_fuzz_cloud STATIC src/ros/cloud_conversion.cpp test/fuzz/fuzz_cloud_entry.cpp)
  target_compile_options(freeform_fuzz_cloud PRIVATE ${FREEFORM_FUZZ_COMPILE_OPTIONS})
  target_include_directories(freeform_fuzz_cloud PUBLIC test/fuzz src/ros)
  target_include_directories(freeform_fuzz_cloud SYSTEM PUBLIC ${FREEFORM_FUZZ_ROS_INCLUDE_DIR})
  target_link_libraries(freeform_fuzz_cloud PUBLIC freeform_inspection_core
    ${FREEFORM_FUZZ_ROS_LIBRARIES})
  freeform_add_fuzz_target(cloud freeform_fuzz_cloud)
else()
  message(WARNING "sensor_msgs headers or roscpp_serialization not found: no fuzz_cloud target")
endif()
