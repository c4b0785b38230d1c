# FindMeshLab2025.cmake — what a plugin for MeshLab 2025.07 builds and links against.
#
#   find_package(MeshLab2025 REQUIRED COMPONENTS d f)     # d: double, f: float (single)
#
# The headers (src/common, vcglib) are those of the checksum-pinned MeshLab 2025.07 sources
# (MeshLab2025Sources.cmake: MESHLAB2025_DIR, a local tarball, or a download). The libmeshlab-common
# a plugin links against is the host's own:
#   d  the one of the PyMeshLab 2025.7 wheel (double precision), in GROWTH_PYMESHLAB_DIR/lib/ (the
#      installed `pymeshlab` package folder); the plugin links the wheel's Qt libraries too, so that
#      every symbol it needs is checked against the wheel at link time;
#   f  a single-precision build of it from the same sources, in MESHLAB2025_DIR/build-float/
#      (scripts/setup.sh --meshlab-2025), the precision of Debian's MeshLab 2025.07 GUI.
#
# Defines, for each component P asked for:
#   MeshLab2025P::vcglib  INTERFACE: vcglib + Eigen + MeshLab 2025.07's src (+ our forwarding header
#                         meshlab_compat/meshlab2025/common/ml_mesh_type.h), MESHLAB_SCALAR=double or
#                         float, MESHLAB_VERSION (2025.07d or 2025.07), GROWTH_MESHLAB_2025. No Qt.
#   MeshLab2025P::plylib  vcglib's PLY reader/writer for it
#   MeshLab2025P::common  IMPORTED: that libmeshlab-common.so with the Qt5 usage a plugin needs
#   MeshLab2025_P_VERSION the version string a plugin reports (ML_VERSION, + "d" for double)
#   MeshLab2025_P_LIBDIR  the folder of that libmeshlab-common (a host's run-time library path)
#   MeshLab2025_P_FOUND, MeshLab2025_FOUND

include(MeshLab2025Sources)
set(MESHLAB2025_DIR "${PROJECT_SOURCE_DIR}/third_party/meshlab-2025.07" CACHE PATH
    "MeshLab 2025.07 sources (scripts/setup.sh); fetched into the build tree when they are not there")
set(GROWTH_PYMESHLAB_DIR "" CACHE PATH
    "The installed pymeshlab 2025.7 package folder (site-packages/pymeshlab): the double-precision host")

# Without GROWTH_PYMESHLAB_DIR, the double build asks the Python interpreter (the one pip builds
# with, or the first on PATH) where its pymeshlab is, without importing it.
if("d" IN_LIST MeshLab2025_FIND_COMPONENTS AND NOT GROWTH_PYMESHLAB_DIR)
  find_package(Python COMPONENTS Interpreter QUIET)
  if(Python_EXECUTABLE)
    execute_process(COMMAND "${Python_EXECUTABLE}" -c
        "import importlib.util, importlib.metadata, os; s = importlib.util.find_spec('pymeshlab'); print(os.path.dirname(s.origin) + ';' + importlib.metadata.version('pymeshlab'))"
        OUTPUT_VARIABLE _pml OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET RESULT_VARIABLE _pml_rc)
    if(_pml_rc EQUAL 0)
      list(GET _pml 0 _pml_dir)
      list(GET _pml 1 _pml_version)
      if(NOT _pml_version MATCHES "^2025\\.7")
        message(FATAL_ERROR "pymeshlab ${_pml_version} found by ${Python_EXECUTABLE} in ${_pml_dir}: "
                "these plugins are built for pymeshlab 2025.7 (pip install pymeshlab==2025.7.post1)")
      endif()
      set(GROWTH_PYMESHLAB_DIR "${_pml_dir}" CACHE PATH "" FORCE)
      message(STATUS "pymeshlab ${_pml_version}: ${_pml_dir}")
    endif()
  endif()
endif()

growth_meshlab2025_sources(_ml2025_src)
set(MeshLab2025_INCLUDE_DIR "${_ml2025_src}/src")
set(MeshLab2025_VCGLIB_DIR "${_ml2025_src}/src/vcglib")
find_path(MeshLab2025_EIGEN_DIR Eigen/Core PATHS /usr/include/eigen3 /usr/local/include/eigen3)
find_path(MeshLab2025_GLEW_INCLUDE_DIR GL/glew.h) # MeshLab's plugin headers include it (no GLEW call is linked)
file(READ "${_ml2025_src}/ML_VERSION" _ml2025_version)
string(STRIP "${_ml2025_version}" _ml2025_version)
# vcglib includes Eigen as "../../eigenlib/Eigen/..."; Debian's sources leave the bundled copy out.
if(MeshLab2025_EIGEN_DIR AND NOT EXISTS "${MeshLab2025_VCGLIB_DIR}/eigenlib/Eigen/Core")
  file(CREATE_LINK "${MeshLab2025_EIGEN_DIR}" "${MeshLab2025_VCGLIB_DIR}/eigenlib" SYMBOLIC)
endif()

set(_ml2025_qt Core Gui Widgets OpenGL Xml)
foreach(_p IN LISTS MeshLab2025_FIND_COMPONENTS)
  set(MeshLab2025_${_p}_FOUND FALSE)
  set(MeshLab2025_${_p}_COMMON_LIBRARY "")
  if(_p STREQUAL "d")
    set(MeshLab2025_d_SCALAR double)
    set(MeshLab2025_d_VERSION "${_ml2025_version}d")
    if(GROWTH_PYMESHLAB_DIR AND EXISTS "${GROWTH_PYMESHLAB_DIR}/lib/libmeshlab-common.so")
      set(MeshLab2025_d_COMMON_LIBRARY "${GROWTH_PYMESHLAB_DIR}/lib/libmeshlab-common.so")
    endif()
  elseif(_p STREQUAL "f")
    set(MeshLab2025_f_SCALAR float)
    set(MeshLab2025_f_VERSION "${_ml2025_version}")
    if(EXISTS "${MESHLAB2025_DIR}/build-float/src/distrib/libmeshlab-common.so")
      set(MeshLab2025_f_COMMON_LIBRARY "${MESHLAB2025_DIR}/build-float/src/distrib/libmeshlab-common.so")
    endif()
  else()
    message(FATAL_ERROR "FindMeshLab2025: unknown component '${_p}' (d: double, f: float)")
  endif()
  if(MeshLab2025_${_p}_COMMON_LIBRARY)
    set(MeshLab2025_${_p}_FOUND TRUE)
    get_filename_component(MeshLab2025_${_p}_LIBDIR "${MeshLab2025_${_p}_COMMON_LIBRARY}" DIRECTORY)
  endif()
endforeach()

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MeshLab2025
  REQUIRED_VARS MeshLab2025_INCLUDE_DIR MeshLab2025_VCGLIB_DIR MeshLab2025_EIGEN_DIR MeshLab2025_GLEW_INCLUDE_DIR
  HANDLE_COMPONENTS
  FAIL_MESSAGE "MeshLab 2025.07 not found. Headers: Eigen (libeigen3-dev) and GLEW (libglew-dev) are needed. \
Libraries: the double build (d) links the PyMeshLab 2025.7 wheel's libmeshlab-common, so set \
GROWTH_PYMESHLAB_DIR to the installed pymeshlab package folder (pip install pymeshlab==2025.7.post1). \
the float build (f) needs scripts/setup.sh --meshlab-2025")

if(MeshLab2025_FOUND)
  find_package(Qt5 QUIET COMPONENTS ${_ml2025_qt})
  if(NOT Qt5_FOUND)
    message(FATAL_ERROR "FindMeshLab2025: Qt 5 development files missing (Qt5 ${_ml2025_qt}): "
      "apt install qtbase5-dev libqt5opengl5-dev")
  endif()
  set(_dirs "${PROJECT_SOURCE_DIR}/meshlab_compat/meshlab2025;${MeshLab2025_VCGLIB_DIR};${MeshLab2025_EIGEN_DIR};${MeshLab2025_INCLUDE_DIR};${MeshLab2025_GLEW_INCLUDE_DIR}")
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

    # Qt: the headers of the system's Qt 5 (moc too), the libraries of the host where it ships its
    # own (the wheel's Qt 5.15.2; Qt keeps 5.15's binary interface across patch releases).
    set(_qt_libs "")
    foreach(_m IN LISTS _ml2025_qt)
      if(_p STREQUAL "d" AND EXISTS "${MeshLab2025_d_LIBDIR}/libQt5${_m}.so.5")
        set(_t MeshLab2025d::Qt5${_m})
        add_library(${_t} SHARED IMPORTED)
        get_target_property(_inc Qt5::${_m} INTERFACE_INCLUDE_DIRECTORIES)
        get_target_property(_def Qt5::${_m} INTERFACE_COMPILE_DEFINITIONS)
        set_target_properties(${_t} PROPERTIES IMPORTED_LOCATION "${MeshLab2025_d_LIBDIR}/libQt5${_m}.so.5"
          IMPORTED_SONAME "libQt5${_m}.so.5" INTERFACE_INCLUDE_DIRECTORIES "${_inc}"
          INTERFACE_COMPILE_DEFINITIONS "${_def}")
        # Qt built with -reduce-relocations needs position-independent code in executables too
        # (ml_apply), which Qt5::Core asks for through these two properties.
        foreach(_prop INTERFACE_COMPILE_OPTIONS INTERFACE_POSITION_INDEPENDENT_CODE INTERFACE_COMPILE_FEATURES)
          get_target_property(_v Qt5::${_m} ${_prop})
          if(_v)
            set_target_properties(${_t} PROPERTIES ${_prop} "${_v}")
          endif()
        endforeach()
        list(APPEND _qt_libs ${_t})
      else()
        list(APPEND _qt_libs Qt5::${_m})
      endif()
    endforeach()

    add_library(MeshLab2025${_p}::common SHARED IMPORTED)
    set_target_properties(MeshLab2025${_p}::common PROPERTIES
      IMPORTED_LOCATION "${MeshLab2025_${_p}_COMMON_LIBRARY}" IMPORTED_SONAME "libmeshlab-common.so")
    # The host library's own dependencies (the wheel's libexternal-glew.so, ...) are found beside it.
    target_link_libraries(MeshLab2025${_p}::common INTERFACE MeshLab2025${_p}::vcglib ${_qt_libs}
                          "-Wl,-rpath-link,${MeshLab2025_${_p}_LIBDIR}")
  endforeach()
endif()
