# Every third-party library, found once. See README "Dependencies" for what each one does.
find_package(Threads REQUIRED)          # before glslang: its targets use Threads::Threads
find_package(Vulkan REQUIRED COMPONENTS glslangValidator)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(OpenEXR REQUIRED)
find_package(Imath REQUIRED)
find_package(PNG REQUIRED)
find_package(fmt REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(STB REQUIRED IMPORTED_TARGET GLOBAL stb)
if(OBSCURA_BUILD_TESTS)
  find_package(GTest REQUIRED)
endif()
