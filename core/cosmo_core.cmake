# The ROS-free core of cosmo: one library per module (include/cosmo/<module>, src/<module>), cosmo_core over all of
# them, and the programs and gtests that need no ROS. Included by core/CMakeLists.txt (the core as a CMake project
# of its own, no catkin) and by the catkin package's CMakeLists.txt, in the including directory's scope (the same
# build folder, so both builds compile the same commands). COSMO_ROOT: the repository; COSMO_BUILD_TESTING: the
# core's gtests.
# The compile settings of both builds: the same here for both, so that a core object's compile command is the same
# in each and ccache compiles it once.
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE RelWithDebInfo)
endif()
set(CMAKE_POSITION_INDEPENDENT_CODE ON)
add_compile_options(-Wall -Wextra -Wno-unused-parameter)

find_package(Eigen3 REQUIRED)
find_package(PCL REQUIRED COMPONENTS common io kdtree search features)  # PCD files (common), FPFH (registration)
find_package(nlohmann_json 3 REQUIRED)
find_package(LibLZMA REQUIRED)
find_package(yaml-cpp REQUIRED)
find_package(TBB REQUIRED)
find_package(nanoflann QUIET)
find_package(Ceres REQUIRED)   # the backend module only (pose-graph check of datasets)
find_package(OpenSSL REQUIRED COMPONENTS Crypto)  # MD5 of ROS 1 message definitions (nebula), SHA-256 (suite)
find_package(CLI11 REQUIRED)   # option parsing (header-only, Debian libcli11-dev)
find_package(SQLite3 REQUIRED)  # ROS 2 bags (trials/ros2_bag.cpp)
find_package(BZip2 REQUIRED)    # ROS 1 bag chunks (trials/ros1_chunk.cpp)
find_package(PkgConfig REQUIRED)
pkg_check_modules(LZ4 REQUIRED IMPORTED_TARGET liblz4)
find_package(ZLIB REQUIRED)     # CRC-32 of the recorder's journal (dataset/measurement_journal.cpp)

# One library per module. DEPS names other modules; USES the third-party targets its public headers need,
# PRIVATE those only its sources need, so each module links what it uses.
set(COSMO_MODULES "")
function(cosmo_module NAME)
  cmake_parse_arguments(M "" "" "DEPS;USES;PRIVATE" ${ARGN})
  file(GLOB _src CONFIGURE_DEPENDS ${COSMO_ROOT}/src/${NAME}/*.cpp)
  add_library(cosmo_${NAME} ${_src})
  set(_deps "")
  foreach(d ${M_DEPS})
    list(APPEND _deps cosmo_${d})
  endforeach()
  target_link_libraries(cosmo_${NAME} PUBLIC ${_deps} ${M_USES} PRIVATE ${M_PRIVATE})
  set(COSMO_MODULES ${COSMO_MODULES} ${NAME} PARENT_SCOPE)
endfunction()

cosmo_module(common USES Eigen3::Eigen yaml-cpp CLI11::CLI11 PRIVATE ${PCL_LIBRARIES})
cosmo_module(jrl DEPS common PRIVATE nlohmann_json::nlohmann_json)
cosmo_module(sim DEPS common PRIVATE TBB::tbb)
cosmo_module(odometry DEPS common)
cosmo_module(place_recognition DEPS common)     # nanoflann: header-only
cosmo_module(registration DEPS common PRIVATE ${PCL_LIBRARIES})
cosmo_module(comm DEPS common USES nlohmann_json::nlohmann_json PRIVATE LibLZMA::LibLZMA)
cosmo_module(dataset DEPS common jrl PRIVATE ZLIB::ZLIB)  # zlib: the journal's CRC-32
cosmo_module(backend DEPS common jrl PRIVATE Ceres::ceres nlohmann_json::nlohmann_json)  # Ceres only here
cosmo_module(report DEPS common jrl comm)  # comm: the connectivity figure
cosmo_module(sequence DEPS common registration dataset sim)   # what a sequence is (below the trials)
cosmo_module(cache)  # the on-disk caches: roots, entries, size limits (cache/cache.hpp)
cosmo_module(trials DEPS common cache sequence PRIVATE SQLite::SQLite3 BZip2::BZip2 PkgConfig::LZ4)
cosmo_module(frontend DEPS common odometry place_recognition registration dataset sequence)  # one robot
cosmo_module(live DEPS common)  # the policies of a distributed run
cosmo_module(pipeline DEPS common jrl sim odometry place_recognition registration comm dataset sequence trials frontend)
cosmo_module(nebula DEPS common jrl dataset PRIVATE OpenSSL::Crypto)
cosmo_module(suite DEPS common jrl comm registration backend pipeline trials
             PRIVATE nlohmann_json::nlohmann_json OpenSSL::Crypto yaml-cpp)

# cosmo_core: every core module, for users of the package (catkin exports it).
add_library(cosmo_core ${COSMO_ROOT}/src/core_version.cpp)
foreach(m ${COSMO_MODULES})
  target_link_libraries(cosmo_core PUBLIC cosmo_${m})
endforeach()

# Synthetic inputs of the tests and benchmarks, not part of cosmo_core (include/cosmo/test_support): scenes built
# of the simulator's primitives and swept by its ScanSimulator (a street, a corridor, a pillar field, the campus).
file(GLOB _test_support_src CONFIGURE_DEPENDS ${COSMO_ROOT}/src/test_support/*.cpp)
add_library(cosmo_test_support ${_test_support_src})
target_link_libraries(cosmo_test_support PUBLIC cosmo_sim)

# A program: src/<KIND>/<module>/<name>.cpp, executable <name>, linked with LIBS (its module's library and what
# it includes beyond that). Tools are also commands on the PATH of the catkin workspace (cosmo_command, defined by
# ../CMakeLists.txt). Every program is named in one such list, here or in ../CMakeLists.txt (ROS glue users).
function(cosmo_program KIND PATH)
  cmake_parse_arguments(P "" "" "LIBS" ${ARGN})
  get_filename_component(_exe ${PATH} NAME)
  set(_name ${_exe})
  if(TARGET ${_exe})            # e.g. the tool cosmo_jrl beside the library cosmo_jrl
    set(_name ${_exe}_tool)
  endif()
  set(_src ${COSMO_ROOT}/src/${KIND}/${PATH}.cpp)
  add_executable(${_name} ${_src})
  set_target_properties(${_name} PROPERTIES OUTPUT_NAME ${_exe})
  target_link_libraries(${_name} ${P_LIBS})
  set_property(GLOBAL APPEND PROPERTY COSMO_LISTED_SOURCES ${_src})
  if(DEFINED CATKIN_PACKAGE_BIN_DESTINATION)
    install(TARGETS ${_name} RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
    if(KIND STREQUAL "tools")
      cosmo_command(${_name} ${_exe})
    endif()
  else()
    install(TARGETS ${_name} RUNTIME DESTINATION bin)
  endif()
  set(COSMO_PROGRAM_TARGET ${_name} PARENT_SCOPE)
endfunction()

cosmo_program(tools cache/cosmo_cache LIBS cosmo_cache cosmo_common)
cosmo_program(tools comm/comm_simulate LIBS cosmo_comm)
cosmo_program(tools dataset/cosmo_noise_models LIBS cosmo_dataset)
cosmo_program(tools jrl/cosmo_jrl LIBS cosmo_jrl cosmo_backend cosmo_report cosmo_dataset)
cosmo_program(tools odometry/cosmo_lidar_odometry LIBS cosmo_odometry cosmo_trials)
cosmo_program(tools pipeline/cosmo_check LIBS cosmo_trials)
cosmo_program(tools pipeline/cosmo_generate LIBS cosmo_pipeline cosmo_backend cosmo_report)
cosmo_program(tools place_recognition/cosmo_scancontext LIBS cosmo_place_recognition)
cosmo_program(tools registration/cosmo_register LIBS cosmo_registration)
cosmo_program(tools suite/cosmo_suite LIBS cosmo_suite cosmo_dataset)
cosmo_program(bench backend/bench_backend LIBS cosmo_backend cosmo_report)
cosmo_program(bench comm/bench_comm LIBS cosmo_comm)
cosmo_program(bench dataset/bench_closure_errors LIBS cosmo_dataset)
cosmo_program(bench dataset/bench_outlier_sweep LIBS cosmo_dataset cosmo_backend)
cosmo_program(bench dataset/bench_recorder LIBS cosmo_dataset)
cosmo_program(bench jrl/bench_jrl_io LIBS cosmo_jrl)
cosmo_program(bench common/bench_kd_trees LIBS cosmo_test_support)
cosmo_program(bench odometry/bench_odometry LIBS cosmo_odometry cosmo_test_support)
cosmo_program(bench pipeline/bench_keyframe_memory LIBS cosmo_pipeline cosmo_dataset)
cosmo_program(bench pipeline/bench_sequence_speed LIBS cosmo_pipeline)
cosmo_program(bench place_recognition/bench_scancontext LIBS cosmo_place_recognition cosmo_test_support)
cosmo_program(bench place_recognition/bench_scancontext_sim LIBS cosmo_place_recognition cosmo_odometry cosmo_trials)
cosmo_program(bench registration/bench_features LIBS cosmo_registration)
cosmo_program(bench registration/bench_registration LIBS cosmo_registration)
cosmo_program(bench trials/bench_scan_cache LIBS cosmo_trials)
cosmo_program(bench registration/bench_registration_sim LIBS cosmo_registration cosmo_odometry cosmo_trials)
cosmo_program(bench sim/bench_sim LIBS cosmo_sim TBB::tbb)

# A gtest: test/<module>/<name>.cpp, target <module>_<name>, linked with LIBS and gtest's main. Under catkin it
# is catkin's gtest (results in test_results/, `make run_tests`); on its own, a ctest test writing the same XML.
function(cosmo_gtest TARGET SRC)
  cmake_parse_arguments(T "" "" "LIBS" ${ARGN})
  if(COMMAND catkin_add_gtest)
    catkin_add_gtest(${TARGET} ${SRC})
    target_link_libraries(${TARGET} ${T_LIBS} ${GTEST_MAIN_LIBRARIES})
  else()
    add_executable(${TARGET} EXCLUDE_FROM_ALL ${SRC})
    target_link_libraries(${TARGET} ${T_LIBS} GTest::gtest_main)
    add_dependencies(tests ${TARGET})
    add_test(NAME ${TARGET} COMMAND ${TARGET} --gtest_output=xml:${CMAKE_BINARY_DIR}/test_results/cosmo/gtest-${TARGET}.xml)
  endif()
  set_property(GLOBAL APPEND PROPERTY COSMO_LISTED_SOURCES ${SRC})
endfunction()

# test/<module>/test_*.cpp link their module (all of the core where the folder is no module) and what they
# include beyond it (COSMO_TEST_LIBS_<target>). The gtests in COSMO_ROS_GTESTS use the ROS glue,
# or run programs that do (cosmo_generate, cosmo_simulate) or the devel space: ../CMakeLists.txt builds them.
set(COSMO_ROS_GTESTS fuzz/test_fuzz_inputs multihost/test_netns_team nebula/test_conversion
    nebula/test_message_definition ros/test_loopback_alias ros/test_markers ros/test_point_cloud
    ros/test_team_sequence_msg sim/test_sim_bag tools/test_suite_end_to_end tools/test_tools_on_fixtures
    trials/test_conformance trials/test_layouts_end_to_end trials/test_ros1_bag trials/test_trial_layouts workspace/test_commands_on_path)
# The core's own gtests: only where COSMO_BUILD_TESTING is on (core/CMakeLists.txt; the catkin package leaves them
# to it and builds the ones above).
if(NOT COSMO_BUILD_TESTING)
  return()
endif()
set(COSMO_TEST_LIBS_backend_test_pose_graph_solver Ceres::ceres)
set(COSMO_TEST_LIBS_dataset_test_outlier_injection cosmo_backend)
set(COSMO_TEST_LIBS_frontend_test_kept_scan cosmo_pipeline cosmo_dataset)
set(COSMO_TEST_LIBS_pipeline_test_lookalike_closures cosmo_dataset)
set(COSMO_TEST_LIBS_pipeline_test_sequence_noise_models cosmo_dataset)
set(COSMO_TEST_LIBS_sequence_test_gate_threshold cosmo_frontend)
set(COSMO_TEST_LIBS_sequence_test_sequence_timing cosmo_frontend cosmo_sim)
set(COSMO_TEST_LIBS_sequence_test_trial_coverage cosmo_odometry)
set(COSMO_TEST_LIBS_sim_test_scan_simulator TBB::tbb)
set(COSMO_TEST_LIBS_trials_test_stamp_convention cosmo_odometry)
file(GLOB _test_dirs LIST_DIRECTORIES true ${COSMO_ROOT}/test/*)
foreach(d ${_test_dirs})
  get_filename_component(_module ${d} NAME)
  if(IS_DIRECTORY ${d} AND NOT _module STREQUAL "rostest" AND NOT _module STREQUAL "data")
    file(GLOB _tests CONFIGURE_DEPENDS ${d}/test_*.cpp)
    foreach(t ${_tests})
      get_filename_component(_name ${t} NAME_WE)
      if(NOT "${_module}/${_name}" IN_LIST COSMO_ROS_GTESTS)
        set(_lib cosmo_core)
        if(TARGET cosmo_${_module})
          set(_lib cosmo_${_module})
        endif()
        cosmo_gtest(${_module}_${_name} ${t} LIBS ${_lib} cosmo_test_support ${COSMO_TEST_LIBS_${_module}_${_name}})
      endif()
    endforeach()
  endif()
endforeach()
