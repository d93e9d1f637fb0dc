//===- PlcProject.cpp - a PLC project given as a directory or project file
//-===//
//
// `netlift translate DIR` and `netlift translate X.plcproj` read a whole
// project as one design: expandProjectInputs turns such an argument into the
// source files it stands for before the frontends read them. A TwinCAT
// `.plcproj` (MSBuild XML) lists its sources as `<Compile Include="...">`;
// a directory stands for the `.plcproj` files under it, or, when it has
// none, for every PLC source file under it (ST, IL, TwinCAT), in name order
// so that a translation does not depend on the order a file system lists.
//
//===----------------------------------------------------------------------===//
#include "frontends/FrontendRegistry.h"
#include "frontends/XmlSupport.h"

#include "llvm/ADT/STLExtras.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"

#include <pugixml.hpp>

using namespace netlift;
using llvm::SMLoc;
using llvm::StringRef;

/// The PLC sources a project directory holds: what a TwinCAT project
/// compiles (POUs, GVLs, DUTs, interfaces, tasks) and plain ST and IL files.
static bool isProjectSource(StringRef path) {
  StringRef ext = llvm::sys::path::extension(path);
  for (StringRef known :
       {".st", ".il", ".TcPOU", ".TcGVL", ".TcDUT", ".TcIO", ".TcTTO"})
    if (ext.equals_insensitive(known))
      return true;
  return false;
}

/// Every regular file under `dir` (recursively) that `keep` accepts,
/// sorted.
static std::vector<std::string> filesUnder(StringRef dir,
                                           bool (*keep)(StringRef)) {
  std::vector<std::string> out;
  std::error_code ec;
  for (llvm::sys::fs::recursive_directory_iterator it(dir, ec), end;
       it != end && !ec; it.increment(ec))
    if (it->type() == llvm::sys::fs::file_type::regular_file &&
        keep(it->path()))
      out.push_back(it->path());
  llvm::sort(out);
  return out;
}

/// The sources a `.plcproj` compiles, in the order it lists them; files of
/// other kinds (task configurations, visualisations, text lists) are left
/// out and named in a note.
static bool readPlcProject(StringRef path, DiagEngine &diag,
                           std::vector<std::string> &out,
                           FrontendOptions &options) {
  unsigned id = addInputFile(diag.sourceMgr(), path);
  if (!id)
    return false;
  XmlBuffer xml(diag.sourceMgr().getMemoryBuffer(id)->getBuffer());
  pugi::xml_document doc;
  if (!xml.parse(doc, diag))
    return false;
  pugi::xml_node project = doc.child("Project");
  if (!project) {
    diag.error(xml.locOf(doc), "not an MSBuild project file (no <Project> "
                               "element)");
    return false;
  }
  // The project's name (the root of `{attribute 'instance-path'}`): the
  // first project read names the design.
  if (options.projectName.empty()) {
    options.projectName = llvm::sys::path::stem(path).str();
    for (pugi::xml_node group : project.children("PropertyGroup"))
      if (StringRef name = StringRef(group.child("Name").text().get()).trim();
          !name.empty())
        options.projectName = name.str();
  }
  // Compiler defines, for `{IF defined(NAME)}`: NAME or NAME:=VALUE,
  // separated by commas.
  for (pugi::xml_node group : project.children("PropertyGroup"))
    if (pugi::xml_node d = group.child("CompilerDefines")) {
      llvm::SmallVector<StringRef, 8> names;
      StringRef(d.text().get()).split(names, ',', -1, false);
      for (StringRef n : names)
        if (!n.trim().empty()) {
          auto [name, value] = n.split(":=");
          options.defines.push_back((name.trim() + (value.empty() ? "" : "=") +
                                     value.trim().trim('\'').trim('"'))
                                        .str());
        }
    }
  StringRef dir = llvm::sys::path::parent_path(path);
  std::vector<std::string> skipped;
  for (pugi::xml_node group : project.children("ItemGroup"))
    for (pugi::xml_node item : group.children("Compile")) {
      std::string include = item.attribute("Include").value();
      std::replace(include.begin(), include.end(), '\\', '/');
      llvm::SmallString<256> file(dir);
      llvm::sys::path::append(file, include);
      if (!isProjectSource(file)) {
        skipped.push_back(include);
        continue;
      }
      if (!llvm::sys::fs::exists(file)) {
        diag.error(xml.locOf(item),
                   "the project compiles '" + include +
                       "', which does not exist (looked for '" + file + "')");
        return false;
      }
      out.push_back(std::string(file));
    }
  if (!skipped.empty())
    diag.note(xml.locOf(project),
              "not PLC sources, not read: " + llvm::join(skipped, ", "));
  return true;
}

std::optional<std::vector<std::string>>
netlift::expandProjectInputs(llvm::ArrayRef<std::string> paths,
                             DiagEngine &diag, FrontendOptions &options) {
  std::vector<std::string> out;
  for (const std::string &path : paths) {
    if (StringRef(path).endswith_insensitive(".plcproj")) {
      if (!readPlcProject(path, diag, out, options))
        return std::nullopt;
      continue;
    }
    if (path == "-" || !llvm::sys::fs::is_directory(path)) {
      out.push_back(path);
      continue;
    }
    std::vector<std::string> projects = filesUnder(path, [](StringRef p) {
      return llvm::sys::path::extension(p).equals_insensitive(".plcproj");
    });
    if (!projects.empty()) {
      for (const std::string &p : projects)
        if (!readPlcProject(p, diag, out, options))
          return std::nullopt;
      continue;
    }
    std::vector<std::string> files = filesUnder(path, isProjectSource);
    if (files.empty()) {
      diag.error(SMLoc(), "'" + path +
                              "' holds no PLC sources (.st, .il, .TcPOU, "
                              ".TcGVL, .TcDUT, .TcIO, .TcTTO) and no "
                              ".plcproj");
      return std::nullopt;
    }
    llvm::append_range(out, files);
  }
  return out;
}
