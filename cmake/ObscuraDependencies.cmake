# Every third-party library, found once. See README "Dependencies" for what each one does.
find_package(Threads REQUIRED)          # before glslang: its targets use Threads::Threads
find_package(Vulkan REQUIRED COMPONENTS glslangValidator)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(OpenEXR REQUIRED)
find_package(Imath REQUIRED)
find_package(PNG REQUIRED)
find_package(assimp REQUIRED)          # glTF, FBX and OBJ scenes, converted to USD text
find_package(TBB REQUIRED)             # parallel sync of rprims
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET GLOBAL stb)
# OpenSubdiv's CPU library. Not find_package(OpenSubdiv): Debian's OpenSubdivConfig lists static
# libraries the package does not ship, which makes the call a hard error.
find_library(OSD_CPU_LIBRARY osdCPU REQUIRED)
find_path(OSD_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
add_library(OpenSubdiv::osdCPU UNKNOWN IMPORTED GLOBAL)
set_target_properties(OpenSubdiv::osdCPU PROPERTIES
  IMPORTED_LOCATION ${OSD_CPU_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${OSD_INCLUDE_DIR})
# Debian's OpenColorIO CMake config is unusable; its pkg-config file works.
pkg_check_modules(OCIO REQUIRED IMPORTED_TARGET GLOBAL OpenColorIO>=2.1)
pkg_check_modules(LZ4 REQUIRED IMPORTED_TARGET GLOBAL liblz4)      # USD crate files' compression
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET GLOBAL libxxhash)  # content hashes of the texture cache
# libsquish: BC1/BC3 colour texture compression. Not pkg-config: Debian's libsquish.pc names an
# include folder that does not exist.
find_library(SQUISH_LIBRARY squish REQUIRED)
find_path(SQUISH_INCLUDE_DIR squish.h REQUIRED)
add_library(Squish::squish UNKNOWN IMPORTED GLOBAL)
set_target_properties(Squish::squish PROPERTIES
  IMPORTED_LOCATION ${SQUISH_LIBRARY}
  INTERFACE_INCLUDE_DIRECTORIES ${SQUISH_INCLUDE_DIR})
pkg_check_modules(LIBZIP REQUIRED IMPORTED_TARGET GLOBAL libzip)   # USDZ packages
pkg_check_modules(GLFW REQUIRED IMPORTED_TARGET GLOBAL glfw3)      # obscura view's window and input
pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET GLOBAL imgui)     # obscura view's HUD (with its GLFW and Vulkan backends)
pkg_check_modules(LIBXML2 REQUIRED IMPORTED_TARGET GLOBAL libxml-2.0)  # MaterialX documents
if(OBSCURA_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
