//===- Iec61499Devices.cpp - what a system's resources add to applications ===//
//
// A 4diac system's resources hold copies of the blocks mapped to them and
// connections between those copies, which mirror the application's, and
// connections from the resource's own start-up block: 4diac's EMB_RES has
// an E_RESTART named START that the `.sys` file does not list, whose COLD
// event usually INITs the mapped blocks. Dropping those would leave an
// application that never starts; they become one E_RESTART per connection
// in the application's module (`_RES_START_1`: their COLD events come in
// any order, an over-approximation of FORTE's connection order). A
// resource connection between mapped blocks that the application does not
// draw (directly, or inside a subapplication) is warned about: netlift
// reads connections from the application.
//
//===----------------------------------------------------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail;

namespace {

/// The application's connections, with the paths of the networks they
/// are in (`outer.inner.sr.EO -> outer.inner.SETO`), upper case.
void gatherConnections(pugi::xml_node net, const std::string &prefix,
                       std::set<std::string> &out) {
  for (const char *list : {"EventConnections", "DataConnections"})
    for (pugi::xml_node c : child(net, list).children("Connection"))
      out.insert(StringRef(prefix + c.attribute("Source").value() + "->" +
                           prefix + c.attribute("Destination").value())
                     .upper());
  for (pugi::xml_node fb : blocksOf(net))
    if (pugi::xml_node inner = child(fb, "SubAppNetwork"))
      gatherConnections(inner, prefix + fb.attribute("Name").value() + ".",
                        out);
}

/// Does resource `res` use its implicit start-up block (a connection from
/// `START.` while no block of its network is named START)?
bool usesStart(pugi::xml_node res) {
  pugi::xml_node net = child(res, "FBNetwork");
  for (pugi::xml_node fb : blocksOf(net))
    if (StringRef(fb.attribute("Name").value()).equals_insensitive("START"))
      return false;
  for (pugi::xml_node c : child(net, "EventConnections").children("Connection"))
    if (StringRef(c.attribute("Source").value())
            .startswith_insensitive("START."))
      return true;
  return false;
}

} // namespace

void Translator::collectResourceStarts() {
  for (auto &[file, sys] : systems)
    for (pugi::xml_node dev : sys.children("Device"))
      for (pugi::xml_node res : dev.children("Resource"))
        if (usesStart(res)) {
          collect(*findType("E_RESTART", file->src->locOf(res)));
          return;
        }
}

void Translator::resourceConnections(XmlSource &src, pugi::xml_node sys,
                                     pugi::xml_node app) {
  StringRef appName = app.attribute("Name").value();
  std::map<std::string, std::string> mappedFrom; // DEV.RES.BLOCK -> From
  for (pugi::xml_node m : sys.children("Mapping"))
    mappedFrom[StringRef(m.attribute("To").value()).upper()] =
        m.attribute("From").value();
  pugi::xml_node appNet = child(app, "SubAppNetwork");
  if (!appNet)
    appNet = child(app, "FBNetwork");
  std::set<std::string> drawn;
  gatherConnections(appNet, "", drawn);
  for (pugi::xml_node dev : sys.children("Device"))
    for (pugi::xml_node res : dev.children("Resource")) {
      std::string where = std::string(dev.attribute("Name").value()) + "." +
                          res.attribute("Name").value();
      bool start = usesStart(res);
      unsigned starts = 0;
      // `block.port` of the resource as `path.port` of this application,
      // or empty (another application's block, or the start-up block).
      auto inApp = [&](StringRef end) -> std::string {
        auto [blk, port] = end.split('.');
        auto it = mappedFrom.find(StringRef(where + "." + blk.str()).upper());
        if (it == mappedFrom.end())
          return "";
        auto [fromApp, path] = StringRef(it->second).split('.');
        if (!fromApp.equals_insensitive(appName))
          return "";
        return (path + "." + port).str();
      };
      pugi::xml_node net = child(res, "FBNetwork");
      for (const char *list : {"EventConnections", "DataConnections"})
        for (pugi::xml_node c : child(net, list).children("Connection")) {
          StringRef from = c.attribute("Source").value();
          StringRef to = c.attribute("Destination").value();
          SMLoc at = src.locOf(c);
          std::string dest = inApp(to);
          if (start && from.startswith_insensitive("START.")) {
            if (dest.empty())
              continue; // another application's block
            auto [blk, port] = StringRef(dest).rsplit('.');
            if (blk.contains('.'))
              fail(at, "resource '" + where + "' starts '" + blk +
                           "', a block inside a subapplication: netlift "
                           "connects the start-up event to blocks at the "
                           "application's top only");
            std::string inst =
                "_" + net::toIdentifier(res.attribute("Name").value()) +
                "_START_" + std::to_string(++starts);
            b.addInstance(inst, "E_RESTART", at);
            b.addConnection(
                {design.save(inst), design.save(from.split('.').second), at},
                {design.save(blk), design.save(port), at}, at);
            continue;
          }
          std::string source = inApp(from);
          if (source.empty() || dest.empty())
            continue; // a connection of another application's blocks
          if (drawn.count(StringRef(source + "->" + dest).upper()))
            continue;
          diag.warning(at, "connection '" + from + " -> " + to +
                               "' of resource '" + where +
                               "' is not drawn in application '" + appName +
                               "': netlift reads connections from the "
                               "application, so it is not in the model");
        }
    }
}
