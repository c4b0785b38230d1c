# FindMeshLab2025.cmake — the MeshLab 2025.07 SDK that scripts/setup.sh builds from Debian's source
# package: src/common and vcglib unpacked into MESHLAB2025_DIR, libmeshlab-common built there in
# double precision (build-double/: the SDK of PyMeshLab 2025.7 and of MeshLab 2025.07d) and in
# single precision (build-float/: the SDK of the plain MeshLab 2025.07 GUI).
#
#   find_package(MeshLab2025 REQUIRED COMPONENTS d f)     # d: double, f: float (single)
#
# Defines, for each component P of d and f asked for:
#   MeshLab2025P::vcglib  INTERFACE: vcglib + Eigen + MeshLab 2025.07's src (+ our forwarding header
#                         common/ml_mesh_type.h), MESHLAB_SCALAR=double or float, MESHLAB_VERSION
#                         (2025.07d or 2025.07), GROWTH_MESHLAB_2025. No Qt.
#   MeshLab2025P::plylib  vcglib's PLY reader/writer for it
#   MeshLab2025P::common  IMPORTED: that libmeshlab-common.so with the Qt5/GLEW usage a plugin needs
#   MeshLab2025_P_VERSION the version string a plugin reports (ML_VERSION, + "d" for double)
#   MeshLab2025_P_FOUND, MeshLab2025_FOUND

set(MESHLAB2025_DIR "${PROJECT_SOURCE_DIR}/third_party/meshlab-2025.07" CACHE PATH
    "MeshLab 2025.07 sources and its libmeshlab-common builds (scripts/setup.sh)")

find_path(MeshLab2025_INCLUDE_DIR common/plugins/interfaces/filter_plugin.h
          PATHS "${MESHLAB2025_DIR}/src" NO_DEFAULT_PATH)
find_path(MeshLab2025_VCGLIB_DIR vcg/complex/complex.h PATHS "${MESHLAB2025_DIR}/src/vcglib" NO_DEFAULT_PATH)
find_path(MeshLab2025_EIGEN_DIR Eigen/Core PATHS /usr/include/eigen3 /usr/local/include/eigen3)
set(_ml2025_version "")
if(EXISTS "${MESHLAB2025_DIR}/ML_VERSION")
  file(READ "${MESHLAB2025_DIR}/ML_VERSION" _ml2025_version)
  string(STRIP "${_ml2025_version}" _ml2025_version)
endif()

foreach(_p IN LISTS MeshLab2025_FIND_COMPONENTS)
  if(_p STREQUAL "d")
    set(_build build-double)
    set(_scalar double)
    set(_suffix d)
  elseif(_p STREQUAL "f")
    set(_build build-float)
    set(_scalar float)
    set(_suffix "")
  else()
    message(FATAL_ERROR "FindMeshLab2025: unknown component '${_p}' (d: double, f: float)")
  endif()
  find_library(MeshLab2025_${_p}_COMMON_LIBRARY NAMES meshlab-common
               PATHS "${MESHLAB2025_DIR}/${_build}/src/distrib" NO_DEFAULT_PATH)
  set(MeshLab2025_${_p}_FOUND FALSE)
  if(MeshLab2025_${_p}_COMMON_LIBRARY AND _ml2025_version)
    set(MeshLab2025_${_p}_FOUND TRUE)
    set(MeshLab2025_${_p}_VERSION "${_ml2025_version}${_suffix}")
    set(MeshLab2025_${_p}_SCALAR ${_scalar})
  endif()
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MeshLab2025
  REQUIRED_VARS MeshLab2025_INCLUDE_DIR MeshLab2025_VCGLIB_DIR MeshLab2025_EIGEN_DIR
  HANDLE_COMPONENTS
  FAIL_MESSAGE "MeshLab 2025.07 SDK not found in ${MESHLAB2025_DIR}: run scripts/setup.sh")

if(MeshLab2025_FOUND)
  find_package(Qt5 REQUIRED COMPONENTS Core Gui Widgets OpenGL Xml Network)
  find_package(GLEW REQUIRED)
  set(_dirs "${PROJECT_SOURCE_DIR}/meshlab_compat/meshlab2025;${MeshLab2025_VCGLIB_DIR};${MeshLab2025_EIGEN_DIR};${MeshLab2025_INCLUDE_DIR}")
  foreach(_p IN LISTS MeshLab2025_FIND_COMPONENTS)
    if(NOT MeshLab2025_${_p}_FOUND OR TARGET MeshLab2025${_p}::vcglib)
      continue()
    endif()
    add_library(MeshLab2025${_p}::vcglib INTERFACE IMPORTED)
    set_target_properties(MeshLab2025${_p}::vcglib PROPERTIES
      INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_dirs}"
      INTERFACE_INCLUDE_DIRECTORIES "${_dirs}"
      INTERFACE_COMPILE_DEFINITIONS
        "MESHLAB_SCALAR=${MeshLab2025_${_p}_SCALAR};MESHLAB_VERSION=${MeshLab2025_${_p}_VERSION};GROWTH_MESHLAB_2025")

    add_library(vcg_plylib_2025${_p} STATIC "${MeshLab2025_VCGLIB_DIR}/wrap/ply/plylib.cpp")
    target_link_libraries(vcg_plylib_2025${_p} PUBLIC MeshLab2025${_p}::vcglib)
    target_compile_options(vcg_plylib_2025${_p} PRIVATE -w)
    add_library(MeshLab2025${_p}::plylib ALIAS vcg_plylib_2025${_p})

    add_library(MeshLab2025${_p}::common SHARED IMPORTED)
    set_target_properties(MeshLab2025${_p}::common PROPERTIES
      IMPORTED_LOCATION "${MeshLab2025_${_p}_COMMON_LIBRARY}" IMPORTED_SONAME "libmeshlab-common.so")
    target_link_libraries(MeshLab2025${_p}::common INTERFACE
      MeshLab2025${_p}::vcglib Qt5::Core Qt5::Gui Qt5::Widgets Qt5::OpenGL Qt5::Xml Qt5::Network GLEW::GLEW)
  endforeach()
endif()
