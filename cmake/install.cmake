# The installed package: headers, libraries, exported targets (oblique::core, ::accurate, ::batch, ::protocol, ::cases, ::oracle, ::mistakes, ::run, ::client,
# ::properties, ::generators, ::report_files, ::counterexample_reports, ::accuracy_profile,
# ::testing, ::raster,
# ::testing_raster, ::fuzzing, ::fuzzing_replay),
# obliqueConfig.cmake with its version file, and the fuzz seed corpus and dictionary
# (share/oblique/fuzz). oblique::warnings is build-only and never exported.
include(CMakePackageConfigHelpers)
set(OBLIQUE_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/oblique)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/ ${PROJECT_SOURCE_DIR}/protocol/include/
                  ${PROJECT_SOURCE_DIR}/cases/include/ ${PROJECT_SOURCE_DIR}/oracle/include/
                  ${PROJECT_SOURCE_DIR}/mistakes/include/ ${PROJECT_SOURCE_DIR}/run/include/
                  ${PROJECT_SOURCE_DIR}/fuzzing/include/
                  ${PROJECT_SOURCE_DIR}/report_files/include/ ${PROJECT_SOURCE_DIR}/client/include/
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
set(OBLIQUE_EXPORTED oblique_accurate oblique_core oblique_batch oblique_protocol oblique_cases oblique_oracle oblique_mistakes oblique_run oblique_properties
    oblique_client oblique_report_files oblique_counterexample_reports oblique_fuzzing oblique_fuzzing_replay)
if(TARGET oblique_generators)
  list(APPEND OBLIQUE_EXPORTED oblique_generators)
endif()
if(TARGET oblique_testing)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/testing/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.h")
  list(APPEND OBLIQUE_EXPORTED oblique_testing)
endif()
# The accuracy profile (oblique::testing's profile_accuracy() writes it) and counterexample reports.
install(FILES ${PROJECT_SOURCE_DIR}/report/include/oblique/report/accuracy_profile.h
              ${PROJECT_SOURCE_DIR}/report/include/oblique/report/counterexample_report.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/oblique/report)
list(APPEND OBLIQUE_EXPORTED oblique_accuracy_profile)
# The rasterizer (its EGL and OpenGL are found again by the package when it was built with them).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/raster/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
list(APPEND OBLIQUE_EXPORTED oblique_raster)
# The shader runner (oblique/shader), on the rasterizer's GL context.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shader/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
list(APPEND OBLIQUE_EXPORTED oblique_shader)
if(TARGET oblique_testing_raster)
  list(APPEND OBLIQUE_EXPORTED oblique_testing_raster)
endif()
if(TARGET oblique_testing_shader)
  list(APPEND OBLIQUE_EXPORTED oblique_testing_shader)
endif()
install(TARGETS ${OBLIQUE_EXPORTED} EXPORT obliqueTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT obliqueTargets NAMESPACE oblique:: DESTINATION ${OBLIQUE_CMAKE_DIR})

set(OBLIQUE_PACKAGE_HAS_TESTING OFF)
if(TARGET oblique_testing)
  set(OBLIQUE_PACKAGE_HAS_TESTING ON)
endif()
set(OBLIQUE_PACKAGE_RASTER_EGL ${OBLIQUE_RASTER_EGL})
set(OBLIQUE_PACKAGE_HAS_GENERATORS OFF)
if(TARGET oblique_generators)
  set(OBLIQUE_PACKAGE_HAS_GENERATORS ON)
endif()
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/obliqueConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/obliqueConfig.cmake
                              INSTALL_DESTINATION ${OBLIQUE_CMAKE_DIR}
                              PATH_VARS CMAKE_INSTALL_DATADIR)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/obliqueConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/obliqueConfig.cmake
              ${PROJECT_BINARY_DIR}/obliqueConfigVersion.cmake DESTINATION ${OBLIQUE_CMAKE_DIR})

install(DIRECTORY ${PROJECT_SOURCE_DIR}/fuzz/corpus/fuzz_oblique/
        DESTINATION ${CMAKE_INSTALL_DATADIR}/oblique/fuzz/corpus)
install(FILES ${PROJECT_SOURCE_DIR}/fuzz/fuzz_oblique.dict
        DESTINATION ${CMAKE_INSTALL_DATADIR}/oblique/fuzz RENAME oblique.dict)

# pkg-config files beside the CMake package (lib/pkgconfig): oblique (core and protocol),
# oblique-testing, oblique-testing-raster and oblique-fuzzing, relocatable (the prefix is found
# from the file's place).
file(RELATIVE_PATH OBLIQUE_PC_UP "/prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/prefix")
string(REGEX REPLACE "/$" "" OBLIQUE_PC_UP "${OBLIQUE_PC_UP}")
set(OBLIQUE_PC_FILES oblique oblique-fuzzing)
if(TARGET oblique_testing)
  list(APPEND OBLIQUE_PC_FILES oblique-testing)
endif()
if(TARGET oblique_testing_raster)
  list(APPEND OBLIQUE_PC_FILES oblique-testing-raster)
  set(OBLIQUE_PC_RASTER_REQUIRES "")
  if(OBLIQUE_RASTER_EGL)
    set(OBLIQUE_PC_RASTER_REQUIRES "egl opengl")
  endif()
endif()
foreach(pc IN LISTS OBLIQUE_PC_FILES)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/pkgconfig/${pc}.pc.in ${PROJECT_BINARY_DIR}/pkgconfig/${pc}.pc
                 @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/pkgconfig/${pc}.pc
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
endforeach()

# The command-line tool (bin/oblique).
if(TARGET oblique)
  install(TARGETS oblique RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
