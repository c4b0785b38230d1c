# FindMeshLab2025.cmake — the MeshLab 2025.07 SDK that scripts/setup.sh builds from Debian's source
# package: src/common and vcglib unpacked into MESHLAB2025_DIR, libmeshlab-common built there in
# double precision (the SDK of PyMeshLab 2025.7 and of MeshLab 2025.07d).
#
# Defines
#   MeshLab2025d::vcglib  INTERFACE: vcglib + Eigen + MeshLab 2025.07's src (+ our forwarding header
#                         common/ml_mesh_type.h), MESHLAB_SCALAR=double, MESHLAB_VERSION=2025.07d,
#                         GROWTH_MESHLAB_2025. No Qt.
#   MeshLab2025d::plylib  vcglib's PLY reader/writer for it
#   MeshLab2025d::common  IMPORTED: that libmeshlab-common.so with the Qt5/GLEW usage a plugin needs
#   MeshLab2025_VERSION   the version string a plugin reports (ML_VERSION + "d")
#   MeshLab2025_FOUND

set(MESHLAB2025_DIR "${PROJECT_SOURCE_DIR}/third_party/meshlab-2025.07" CACHE PATH
    "MeshLab 2025.07 sources and its double-precision libmeshlab-common (scripts/setup.sh)")

find_path(MeshLab2025_INCLUDE_DIR common/plugins/interfaces/filter_plugin.h
          PATHS "${MESHLAB2025_DIR}/src" NO_DEFAULT_PATH)
find_path(MeshLab2025_VCGLIB_DIR vcg/complex/complex.h PATHS "${MESHLAB2025_DIR}/src/vcglib" NO_DEFAULT_PATH)
find_library(MeshLab2025_COMMON_LIBRARY NAMES meshlab-common
             PATHS "${MESHLAB2025_DIR}/build-double/src/distrib" NO_DEFAULT_PATH)
find_path(MeshLab2025_EIGEN_DIR Eigen/Core PATHS /usr/include/eigen3 /usr/local/include/eigen3)
if(EXISTS "${MESHLAB2025_DIR}/ML_VERSION")
  file(READ "${MESHLAB2025_DIR}/ML_VERSION" _ml2025_version)
  string(STRIP "${_ml2025_version}" _ml2025_version)
  set(MeshLab2025_VERSION "${_ml2025_version}d")
endif()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MeshLab2025
  REQUIRED_VARS MeshLab2025_INCLUDE_DIR MeshLab2025_VCGLIB_DIR MeshLab2025_EIGEN_DIR
                MeshLab2025_COMMON_LIBRARY MeshLab2025_VERSION
  FAIL_MESSAGE "MeshLab 2025.07d SDK not found in ${MESHLAB2025_DIR}: run scripts/setup.sh")

if(MeshLab2025_FOUND AND NOT TARGET MeshLab2025d::vcglib)
  set(_dirs "${PROJECT_SOURCE_DIR}/meshlab_compat/meshlab2025;${MeshLab2025_VCGLIB_DIR};${MeshLab2025_EIGEN_DIR};${MeshLab2025_INCLUDE_DIR}")
  add_library(MeshLab2025d::vcglib INTERFACE IMPORTED)
  set_target_properties(MeshLab2025d::vcglib PROPERTIES
    INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_dirs}"
    INTERFACE_INCLUDE_DIRECTORIES "${_dirs}"
    INTERFACE_COMPILE_DEFINITIONS "MESHLAB_SCALAR=double;MESHLAB_VERSION=${MeshLab2025_VERSION};GROWTH_MESHLAB_2025")

  add_library(vcg_plylib_2025d STATIC "${MeshLab2025_VCGLIB_DIR}/wrap/ply/plylib.cpp")
  target_link_libraries(vcg_plylib_2025d PUBLIC MeshLab2025d::vcglib)
  target_compile_options(vcg_plylib_2025d PRIVATE -w)
  add_library(MeshLab2025d::plylib ALIAS vcg_plylib_2025d)

  find_package(Qt5 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml Network)
  find_package(GLEW REQUIRED)
  add_library(MeshLab2025d::common SHARED IMPORTED)
  set_target_properties(MeshLab2025d::common PROPERTIES IMPORTED_LOCATION "${MeshLab2025_COMMON_LIBRARY}")
  target_link_libraries(MeshLab2025d::common INTERFACE
    MeshLab2025d::vcglib Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml Qt5::Network GLEW::GLEW)
endif()
