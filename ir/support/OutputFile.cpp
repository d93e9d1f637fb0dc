//===- OutputFile.cpp - writing an output whole or not at all -------------===//
#include "ir/support/OutputFile.h"

#include "llvm/ADT/SmallString.h"
#include "llvm/Support/FileSystem.h"

using namespace netlift;

bool netlift::writeOutputFile(
    llvm::StringRef path, llvm::function_ref<void(llvm::raw_ostream &)> body,
    DiagEngine &diag) {
  auto cannot = [&](const std::string &why) {
    diag.error(llvm::SMLoc(), "cannot write '" + path + "': " + why);
    return false;
  };
  if (path == "-") {
    body(llvm::outs());
    llvm::outs().flush();
    return true;
  }
  // Renaming a temporary over a device or pipe would replace it with a
  // regular file.
  llvm::sys::fs::file_status st;
  if (!llvm::sys::fs::status(path, st) &&
      st.type() != llvm::sys::fs::file_type::regular_file &&
      st.type() != llvm::sys::fs::file_type::file_not_found) {
    std::error_code ec;
    llvm::raw_fd_ostream os(path, ec);
    if (ec)
      return cannot(ec.message());
    body(os);
    return true;
  }
  llvm::SmallString<128> tmp;
  int fd;
  std::string model = (path + ".tmp-%%%%%%").str();
  if (std::error_code ec = llvm::sys::fs::createUniqueFile(model, fd, tmp))
    return cannot(ec.message());
  {
    llvm::raw_fd_ostream os(fd, /*shouldClose=*/true);
    body(os);
    os.close();
    if (os.has_error()) {
      std::string why = os.error().message();
      os.clear_error();
      llvm::sys::fs::remove(tmp);
      return cannot(why);
    }
  }
  if (std::error_code ec = llvm::sys::fs::rename(tmp, path)) {
    llvm::sys::fs::remove(tmp);
    return cannot(ec.message());
  }
  return true;
}
