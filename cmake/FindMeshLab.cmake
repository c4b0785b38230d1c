# FindMeshLab.cmake — the MeshLab 2020.09 plugin SDK as scripts/setup.sh installs it.
#
# Looks for
#   - MeshLab's plugin API headers (src/common/interfaces.h, ml_mesh_type.h, ...) and vcglib, unpacked
#     from Debian's source package into MESHLAB_SDK_DIR (default: <repo>/third_party/meshlab-sdk);
#   - the installed libmeshlab-common.so and the plugin folder of Debian's meshlab package;
#   - Eigen 3 (vcglib's math).
#
# Defines
#   MeshLab::vcglib   INTERFACE target: vcglib + Eigen + ml_mesh_type.h, MESHLAB_SCALAR=float. No Qt.
#   MeshLab::common   IMPORTED target: libmeshlab-common.so with the Qt5/GLEW usage a plugin needs.
#   MeshLab_PLUGIN_DIR        the plugin folder of the installed MeshLab
#   MeshLab_SERVER_EXECUTABLE meshlabserver
#   MeshLab_FOUND

set(MESHLAB_SDK_DIR "${PROJECT_SOURCE_DIR}/third_party/meshlab-sdk" CACHE PATH
    "MeshLab 2020.09 sources unpacked by scripts/setup.sh (src/common and vcglib)")

set(_meshlab_hint "run scripts/setup.sh (as root or with sudo) to install MeshLab and fetch its SDK")

find_path(MeshLab_INCLUDE_DIR common/interfaces.h
          PATHS "${MESHLAB_SDK_DIR}/src" NO_DEFAULT_PATH)
find_path(MeshLab_VCGLIB_DIR vcg/complex/complex.h
          PATHS "${MESHLAB_SDK_DIR}/vcglib" NO_DEFAULT_PATH)
find_library(MeshLab_COMMON_LIBRARY NAMES meshlab-common
             PATHS /usr/lib/x86_64-linux-gnu/meshlab /usr/lib/meshlab /usr/local/lib/meshlab
             NO_DEFAULT_PATH)
find_path(MeshLab_PLUGIN_DIR NAMES libfilter_clean.so
          PATHS /usr/lib/x86_64-linux-gnu/meshlab/plugins /usr/lib/meshlab/plugins NO_DEFAULT_PATH)
find_program(MeshLab_SERVER_EXECUTABLE meshlabserver)
find_path(MeshLab_EIGEN_DIR Eigen/Core PATHS /usr/include/eigen3 /usr/local/include/eigen3)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MeshLab
  REQUIRED_VARS MeshLab_INCLUDE_DIR MeshLab_VCGLIB_DIR MeshLab_EIGEN_DIR MeshLab_COMMON_LIBRARY
  FAIL_MESSAGE "MeshLab 2020.09 SDK not found: ${_meshlab_hint}")

if(MeshLab_FOUND AND NOT TARGET MeshLab::vcglib)
  # vcglib and MeshLab headers are third-party code: SYSTEM includes silence their warnings.
  add_library(MeshLab::vcglib INTERFACE IMPORTED)
  set_target_properties(MeshLab::vcglib PROPERTIES
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${MeshLab_VCGLIB_DIR};${MeshLab_EIGEN_DIR};${MeshLab_INCLUDE_DIR}"
    INTERFACE_INCLUDE_DIRECTORIES "${MeshLab_VCGLIB_DIR};${MeshLab_EIGEN_DIR};${MeshLab_INCLUDE_DIR}"
    INTERFACE_COMPILE_DEFINITIONS "MESHLAB_SCALAR=float")

  # The ply reader/writer of vcglib is a .cpp of its own; tools and tests link it.
  add_library(vcg_plylib STATIC "${MeshLab_VCGLIB_DIR}/wrap/ply/plylib.cpp")
  target_link_libraries(vcg_plylib PUBLIC MeshLab::vcglib)
  target_compile_options(vcg_plylib PRIVATE -w)
  # Without assertions in every build, as MeshLab ships it: the reader asserts on input it cannot
  # handle (big-endian doubles: SwapDouble is assert(0)), so the sanitizer build and the fuzzers
  # (scripts/sanitize.sh, fuzz.sh) test what the Release build does with such a file.
  target_compile_definitions(vcg_plylib PRIVATE NDEBUG)
  set_target_properties(vcg_plylib PROPERTIES POSITION_INDEPENDENT_CODE ON)
  add_library(MeshLab::plylib ALIAS vcg_plylib)

  find_package(Qt5 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml)
  find_package(GLEW REQUIRED)
  add_library(MeshLab::common SHARED IMPORTED)
  set_target_properties(MeshLab::common PROPERTIES IMPORTED_LOCATION "${MeshLab_COMMON_LIBRARY}")
  target_link_libraries(MeshLab::common INTERFACE
    MeshLab::vcglib Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml GLEW::GLEW)
endif()
