// SPDX-License-Identifier: BSD-3-Clause
// Copyright 2026 The freeform_inspection authors
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>

#include "pcd_header.h"
#include "readers.h"
#include <dlfcn.h>
#include <link.h>

// PCL's PCD reader lives in a module of its own (pcd_reader.cpp): linking PCL's io into the core
// would load VTK and OpenNI into every process, 40 ms before main() on this machine, for a
// format most runs never read. The module sits beside the object that holds this code (the
// core library, or the executable when the core is linked statically) and is opened on the
// first PCD read.

#ifndef FREEFORM_PCD_MODULE_FILE
#error "FREEFORM_PCD_MODULE_FILE must name the PCD module's file (CMakeLists.txt)"
#endif

namespace freeform_inspection {
namespace io_internal {
namespace {

using ReadPcdEntry = void (*)(const std::string*, const PcdHeader*, RawGeometry*, Status*);

struct PcdModule {
  ReadPcdEntry read = nullptr;
  std::string problem;  // why `read` is null
};

std::string directoryOfThisCode() {
  Dl_info info{};
  link_map* object = nullptr;
  if (dladdr1(reinterpret_cast<void*>(&readPcd),
              &info,
              reinterpret_cast<void**>(&object),
              RTLD_DL_LINKMAP) == 0 ||
      object == nullptr) {
    return "";
  }
  // The main program has no name of its own here (dladdr would give argv[0], which may be a bare
  // name found on PATH): its file is /proc/self/exe.
  std::error_code ec;
  const std::filesystem::path file = object->l_name[0] != '\0'
                                         ? std::filesystem::path(object->l_name)
                                         : std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec || !file.has_parent_path() ? "" : file.parent_path().string();
}

PcdModule openModule() {
  PcdModule module;
  const std::string directory = directoryOfThisCode();
  if (directory.empty()) {
    module.problem = "cannot locate the PCD module (dladdr failed)";
    return module;
  }
  const std::string file = directory + "/" + FREEFORM_PCD_MODULE_FILE;
  // Never closed: the reader's code must stay mapped for the process's lifetime.
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* error = dlerror();
    module.problem = "cannot load the PCD module: " + std::string(error ? error : file);
    return module;
  }
  module.read = reinterpret_cast<ReadPcdEntry>(dlsym(handle, "freeform_inspection_read_pcd"));
  if (module.read == nullptr) {
    module.problem = "the PCD module '" + file + "' has no reader entry";
  }
  return module;
}

}  // namespace

Status readPcd(const std::string& path, std::uintmax_t file_size, RawGeometry* out) {
  // Our own strict reading first: PCL allocates from the header while it parses it.
  PcdHeader header;
  Status status = parsePcdHeader(path, &header);
  if (status.ok()) {
    status = checkPcdDataSize(path, header, file_size);
  }
  if (!status.ok()) {
    return status;
  }
  static std::once_flag opened;
  static PcdModule module;
  std::call_once(opened, [] { module = openModule(); });
  if (module.read == nullptr) {
    return Status::failure(StatusCode::kInvalidInput,
                           "cannot read PCD '" + path + "': " + module.problem);
  }
  module.read(&path, &header, out, &status);
  const std::string viewpoint = status.ok() ? pcdViewpointWarning(header) : "";
  if (!viewpoint.empty()) {
    out->warnings.push_back(viewpoint);
  }
  return status;
}

}  // namespace io_internal
}  // namespace freeform_inspection
