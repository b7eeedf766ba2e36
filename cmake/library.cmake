# The installed library: libfaultmesh shared and static, made of the stage
# libraries' objects (compiled once, PIC, hidden symbols); the public
# headers under include/faultmesh; faultmesh.pc; the CMake package
# faultmesh (find_package(faultmesh) -> faultmesh::faultmesh); the Python
# package. Included by the top-level CMakeLists.txt after the stages.

set(FM_PUBLIC_HEADERS
  ${PROJECT_SOURCE_DIR}/include/faultmesh/faultmesh.h
  ${PROJECT_SOURCE_DIR}/include/faultmesh/fm_export.h
  ${PROJECT_SOURCE_DIR}/include/faultmesh/fm_status.h
  ${PROJECT_SOURCE_DIR}/include/faultmesh/fm_run.h
  ${PROJECT_SOURCE_DIR}/include/faultmesh/fm_commands.h
  ${PROJECT_SOURCE_DIR}/include/faultmesh/fm_synthetic.h
  ${PROJECT_SOURCE_DIR}/include/faultmesh/fm_process.h
  ${PROJECT_BINARY_DIR}/include/faultmesh/fm_version.h)

set(fm_objects)
foreach(lib IN LISTS FM_STAGE_LIBS)
  list(APPEND fm_objects $<TARGET_OBJECTS:${lib}>)
endforeach()

# What the stages link from Debian, as the static library's users must
# link it (plain names: Debian keeps them where the linker looks). The
# ones with a .pc file go to faultmesh.pc's Requires.private, the rest to
# its Libs.private. Keep in step with the stages' CMakeLists.txt.
set(FM_PC_REQUIRES_PRIVATE proj cairo fontconfig json-c netcdf lapacke zlib)
get_filename_component(fm_cholmod ${CHOLMOD_LIBRARY} NAME_WE)
get_filename_component(fm_exodus ${FM_EXODUS_LIB} NAME_WE)
string(REGEX REPLACE "^lib" "" fm_cholmod ${fm_cholmod})
string(REGEX REPLACE "^lib" "" fm_exodus ${fm_exodus})
find_package(OpenMP REQUIRED COMPONENTS C)
set(FM_OTHER_LIBS ${fm_cholmod} ${fm_exodus} ${OpenMP_C_LIB_NAMES} pthread ${CMAKE_DL_LIBS} m)
list(REMOVE_DUPLICATES FM_OTHER_LIBS)
set(FM_STATIC_DEPS proj cairo fontconfig json-c netcdf lapacke z ${FM_OTHER_LIBS})

set(fm_build_includes
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
  $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include>
  # the headers include each other by their own names
  $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include/faultmesh>
  $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}/include/faultmesh>
  $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)

set(fm_installed)
if(FM_BUILD_SHARED)
  add_library(faultmesh_shared SHARED ${fm_objects})
  set_target_properties(faultmesh_shared PROPERTIES OUTPUT_NAME faultmesh
    VERSION ${PROJECT_VERSION} SOVERSION ${FM_SOVERSION} EXPORT_NAME faultmesh_shared
    LIBRARY_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib)
  target_include_directories(faultmesh_shared INTERFACE ${fm_build_includes})
  # The objects are all there; linking the stage archives after them pulls
  # no member in and brings each stage's own dependencies (found targets,
  # exact paths), as the CLI gets them.
  target_link_libraries(faultmesh_shared PRIVATE ${FM_STAGE_LIBS})
  # An undefined symbol is an error now rather than in a consumer.
  target_link_options(faultmesh_shared PRIVATE -Wl,--no-undefined)
  add_library(faultmesh::faultmesh_shared ALIAS faultmesh_shared)
  list(APPEND fm_installed faultmesh_shared)
endif()
if(FM_BUILD_STATIC)
  add_library(faultmesh_static STATIC ${fm_objects})
  set_target_properties(faultmesh_static PROPERTIES OUTPUT_NAME faultmesh
    EXPORT_NAME faultmesh_static ARCHIVE_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/lib)
  target_include_directories(faultmesh_static INTERFACE ${fm_build_includes})
  target_link_libraries(faultmesh_static INTERFACE ${FM_STATIC_DEPS})
  add_library(faultmesh::faultmesh_static ALIAS faultmesh_static)
  list(APPEND fm_installed faultmesh_static)
endif()
if(TARGET faultmesh_shared)
  add_library(faultmesh::faultmesh ALIAS faultmesh_shared)
elseif(TARGET faultmesh_static)
  add_library(faultmesh::faultmesh ALIAS faultmesh_static)
endif()

install(FILES ${FM_PUBLIC_HEADERS} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/faultmesh)
set(fm_cmakedir ${CMAKE_INSTALL_LIBDIR}/cmake/faultmesh)
if(TARGET faultmesh_shared)
  install(TARGETS faultmesh_shared EXPORT faultmeshSharedTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(EXPORT faultmeshSharedTargets NAMESPACE faultmesh:: DESTINATION ${fm_cmakedir})
endif()
if(TARGET faultmesh_static)
  install(TARGETS faultmesh_static EXPORT faultmeshStaticTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  install(EXPORT faultmeshStaticTargets NAMESPACE faultmesh:: DESTINATION ${fm_cmakedir})
endif()

include(CMakePackageConfigHelpers)
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/faultmeshConfig.cmake.in
  ${PROJECT_BINARY_DIR}/cmake/faultmeshConfig.cmake INSTALL_DESTINATION ${fm_cmakedir})
# 0.x: a minor version may break the API, so only the same minor matches.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cmake/faultmeshConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cmake/faultmeshConfig.cmake
  ${PROJECT_BINARY_DIR}/cmake/faultmeshConfigVersion.cmake DESTINATION ${fm_cmakedir})

# faultmesh.pc, relocatable: its prefix is found from where it lies, so
# `cmake --install build --prefix DIR` needs no new configure.
set(fm_pcdir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH fm_pc_up /prefix/${fm_pcdir} /prefix)
string(REGEX REPLACE "/$" "" fm_pc_up "${fm_pc_up}")
string(JOIN " " FM_PC_REQUIRES_PRIVATE_TEXT ${FM_PC_REQUIRES_PRIVATE})
set(FM_PC_LIBS_PRIVATE_TEXT "")
foreach(l IN LISTS FM_OTHER_LIBS)
  string(APPEND FM_PC_LIBS_PRIVATE_TEXT " -l${l}")
endforeach()
string(STRIP "${FM_PC_LIBS_PRIVATE_TEXT}" FM_PC_LIBS_PRIVATE_TEXT)
configure_file(${PROJECT_SOURCE_DIR}/cmake/faultmesh.pc.in
  ${PROJECT_BINARY_DIR}/faultmesh.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/faultmesh.pc DESTINATION ${fm_pcdir})

# The Python package (ctypes over the shared library), where Debian's
# python3 looks for packages under the prefix; _config.py tells it where
# the library is from there.
set(FM_INSTALL_PYTHONDIR ${CMAKE_INSTALL_LIBDIR}/python3/dist-packages
    CACHE STRING "Where the Python package faultmesh is installed (under the prefix)")
file(RELATIVE_PATH fm_py_libdir /prefix/${FM_INSTALL_PYTHONDIR}/faultmesh
     /prefix/${CMAKE_INSTALL_LIBDIR})
configure_file(${PROJECT_SOURCE_DIR}/python/faultmesh/_config.py.in
  ${PROJECT_BINARY_DIR}/python/faultmesh/_config.py @ONLY)
file(GLOB fm_py_files CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/python/faultmesh/*.py)
if(TARGET faultmesh_shared)
  install(FILES ${fm_py_files} ${PROJECT_BINARY_DIR}/python/faultmesh/_config.py
    DESTINATION ${FM_INSTALL_PYTHONDIR}/faultmesh)
endif()

# API documentation from the installed headers (Debian's doxygen), with
# docs/library.md as its main page: `cmake --build build --target doc`
# writes build/docs/api/html. Left out when doxygen is absent.
find_package(Doxygen QUIET)
if(DOXYGEN_FOUND)
  set(DOXYGEN_PROJECT_NAME faultmesh)
  set(DOXYGEN_PROJECT_NUMBER ${PROJECT_VERSION})
  set(DOXYGEN_PROJECT_BRIEF "Remeshing of geological fault surfaces: the installed C API")
  set(DOXYGEN_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/docs/api)
  set(DOXYGEN_USE_MDFILE_AS_MAINPAGE ${PROJECT_SOURCE_DIR}/docs/library.md)
  set(DOXYGEN_OPTIMIZE_OUTPUT_FOR_C YES)
  set(DOXYGEN_EXTRACT_ALL YES)
  set(DOXYGEN_GENERATE_LATEX NO)
  set(DOXYGEN_FULL_PATH_NAMES NO)
  set(DOXYGEN_WARN_AS_ERROR NO)
  set(DOXYGEN_QUIET YES)
  # FM_API is an attribute, not part of a declaration's type
  set(DOXYGEN_MACRO_EXPANSION YES)
  set(DOXYGEN_EXPAND_ONLY_PREDEF YES)
  set(DOXYGEN_PREDEFINED "FM_API=")
  doxygen_add_docs(doc ${FM_PUBLIC_HEADERS} ${PROJECT_SOURCE_DIR}/docs/library.md
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    COMMENT "API documentation (build/docs/api/html)")
endif()
