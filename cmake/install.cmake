# SPDX-License-Identifier: MIT
# `cmake --install BUILD [--prefix P]`: the shared and static library, the
# public headers, the CLI with its man page and bash completion, granflow.pc
# (pkg-config) and a CMake package
# (find_package(granflow) -> granflow::granflow, granflow::granflow_static).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set_target_properties(granflow_cli PROPERTIES INSTALL_RPATH "$ORIGIN/../${CMAKE_INSTALL_LIBDIR}")
install(TARGETS granflow granflow_static EXPORT granflowTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS granflow_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The man page (built by the default target; OPTIONAL: a build of granflow_cli
# alone has none) and the bash completion.
install(FILES ${CMAKE_BINARY_DIR}/granflow.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 OPTIONAL)
install(FILES scripts/granflow-completion.bash DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
        RENAME granflow)
install(DIRECTORY include/granflow DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} FILES_MATCHING PATTERN "*.h")
install(FILES ${GF_GENERATED_INCLUDE}/granflow/version.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/granflow)

set(GF_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/granflow)
install(EXPORT granflowTargets NAMESPACE granflow:: DESTINATION ${GF_CMAKE_DIR})
configure_package_config_file(cmake/granflowConfig.cmake.in ${CMAKE_BINARY_DIR}/granflowConfig.cmake
                              INSTALL_DESTINATION ${GF_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/granflowConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/granflowConfig.cmake ${CMAKE_BINARY_DIR}/granflowConfigVersion.cmake
        DESTINATION ${GF_CMAKE_DIR})

# pkg-config: `pkg-config --cflags --libs granflow` (shared), `--static` adds
# what libgranflow.a needs.
if(GF_OPENMP)
  set(GF_PC_OPENMP "-fopenmp")
endif()
# Relocatable: the prefix is ${pcfiledir} (the directory of granflow.pc,
# <prefix>/<libdir>/pkgconfig) and as many `..` as that path has parts, so
# `cmake --install BUILD --prefix P` anywhere, or a moved tree, needs no
# --define-variable. (The CMake package is relocatable by itself: its
# PACKAGE_PREFIX_DIR and _IMPORT_PREFIX are computed from its own place.)
if(IS_ABSOLUTE "${CMAKE_INSTALL_LIBDIR}")
  set(GF_PC_PREFIX "${CMAKE_INSTALL_PREFIX}")
else()
  file(RELATIVE_PATH GF_PC_UP "/gf/${CMAKE_INSTALL_LIBDIR}/pkgconfig" "/gf")
  set(GF_PC_PREFIX "\${pcfiledir}/${GF_PC_UP}")
endif()
configure_file(cmake/granflow.pc.in ${CMAKE_BINARY_DIR}/granflow.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/granflow.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# The Python package, beside the library it loads (it finds <prefix>/lib by
# itself): PYTHONPATH=<prefix>/share/granflow/python.
install(DIRECTORY python/granflow DESTINATION ${CMAKE_INSTALL_DATADIR}/granflow/python
        PATTERN __pycache__ EXCLUDE)
