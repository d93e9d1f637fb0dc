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
// A resource may also hold blocks of its own, mapped from no application
// (4diac lets a user draw them in the resource's editor). They run in
// the resource like mapped ones, so netlift moves them, with their
// connections, into the application mapped to that resource (the same
// event queue; a connection to a mapped block becomes one to the
// application's block), or into an application of their own named after
// the resource when none is mapped to it.
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

std::map<std::string, std::string>
netlift::iec61499::detail::mappingsByTarget(pugi::xml_node sys) {
  std::map<std::string, std::string> out;
  for (pugi::xml_node m : sys.children("Mapping"))
    out[StringRef(m.attribute("To").value()).upper()] =
        m.attribute("From").value();
  return out;
}

void Translator::adoptResourceBlocks(XmlSource &src, pugi::xml_node sys) {
  std::map<std::string, std::string> mappedFrom = mappingsByTarget(sys);
  for (pugi::xml_node dev : sys.children("Device"))
    for (pugi::xml_node res : dev.children("Resource")) {
      std::string where = std::string(dev.attribute("Name").value()) + "." +
                          res.attribute("Name").value();
      pugi::xml_node net = child(res, "FBNetwork");
      std::vector<pugi::xml_node> own;
      std::set<std::string> ownNames; // upper case
      for (pugi::xml_node fb : blocksOf(net))
        if (!mappedFrom.count(
                StringRef(where + "." + fb.attribute("Name").value())
                    .upper())) {
          own.push_back(fb);
          ownNames.insert(StringRef(fb.attribute("Name").value()).upper());
        }
      if (own.empty())
        continue;
      // The applications mapped to this resource.
      std::set<std::string> apps;
      for (auto &[to, from] : mappedFrom)
        if (StringRef(to).startswith(StringRef(where + ".").upper()))
          apps.insert(StringRef(from).split('.').first.upper());
      if (apps.size() > 1)
        fail(src.locOf(own[0]),
             "FB '" + Twine(own[0].attribute("Name").value()) +
                 "' of resource '" + where +
                 "' is mapped from no application, and " + Twine(apps.size()) +
                 " applications are mapped to the resource: netlift "
                 "cannot tell whose event queue it joins (move it into "
                 "one)");
      pugi::xml_node app;
      for (pugi::xml_node a : sys.children("Application"))
        if (apps.count(StringRef(a.attribute("Name").value()).upper()))
          app = a;
      if (!app) {
        std::string name = net::toIdentifier(where);
        for (pugi::xml_node a : sys.children("Application"))
          if (StringRef(name).equals_insensitive(a.attribute("Name").value()))
            fail(src.locOf(res),
                 "resource '" + where +
                     "' has blocks of its own, and the "
                     "application netlift would put them in, '" +
                     name + "', exists already");
        app = sys.insert_child_before("Application", res.parent());
        app.append_attribute("Name") = name.c_str();
      }
      StringRef appName = app.attribute("Name").value();
      pugi::xml_node appNet = child(app, "SubAppNetwork");
      if (!appNet)
        appNet = child(app, "FBNetwork");
      if (!appNet)
        appNet = app.append_child("SubAppNetwork");
      for (pugi::xml_node fb : own) {
        StringRef name = fb.attribute("Name").value();
        for (pugi::xml_node other : blocksOf(appNet))
          if (name.equals_insensitive(other.attribute("Name").value()))
            fail(src.locOf(fb), "FB '" + name + "' of resource '" + where +
                                    "' is mapped from no application, and "
                                    "application '" +
                                    appName +
                                    "' mapped to the resource has a block of "
                                    "that name");
        appNet.append_move(fb);
        pugi::xml_node m = sys.append_child("Mapping");
        m.append_attribute("From") = (appName + "." + name).str().c_str();
        m.append_attribute("To") = (where + "." + name).str().c_str();
      }
      // `block.port` of the resource in the application's terms, or "" when
      // the block is neither the resource's own nor mapped from `app`.
      auto inApp = [&](StringRef end) -> std::string {
        auto [blk, port] = end.split('.');
        if (ownNames.count(blk.upper()))
          return end.str();
        auto it = mappedFrom.find(StringRef(where + "." + blk.str()).upper());
        if (it == mappedFrom.end())
          return "";
        auto [fromApp, path] = StringRef(it->second).split('.');
        if (!fromApp.equals_insensitive(appName) || path.contains('.'))
          return "";
        return (path + "." + port).str();
      };
      for (const char *list : {"EventConnections", "DataConnections"}) {
        std::vector<pugi::xml_node> moved;
        for (pugi::xml_node c : child(net, list).children("Connection")) {
          StringRef from = c.attribute("Source").value();
          StringRef to = c.attribute("Destination").value();
          bool ownFrom = ownNames.count(from.split('.').first.upper());
          bool ownTo = ownNames.count(to.split('.').first.upper());
          if (!ownFrom && !ownTo)
            continue; // between mapped copies, or from the start-up block
          std::string source = inApp(from), dest = inApp(to);
          if (source.empty() &&
              !(from.startswith_insensitive("START.") && usesStart(res)))
            fail(src.locOf(c),
                 "connection '" + from + " -> " + to + "' of resource '" +
                     where + "' joins a block of the resource's own to '" +
                     from + "', which is not a block of application '" +
                     appName + "' at its top");
          if (dest.empty())
            fail(src.locOf(c),
                 "connection '" + from + " -> " + to + "' of resource '" +
                     where + "' joins a block of the resource's own to '" + to +
                     "', which is not a block of application '" + appName +
                     "' at its top");
          if (source.empty())
            continue; // START.COLD: resourceConnections starts the block
          c.attribute("Source") = source.c_str();
          c.attribute("Destination") = dest.c_str();
          moved.push_back(c);
        }
        if (moved.empty())
          continue;
        pugi::xml_node into = child(appNet, list);
        if (!into)
          into = appNet.append_child(list);
        for (pugi::xml_node c : moved)
          into.append_move(c);
      }
      diag.note(src.locOf(own[0]),
                Twine(own.size()) + " FB" + (own.size() == 1 ? "" : "s") +
                    " of resource '" + where +
                    "' mapped from no application run with application '" +
                    appName + "' (the resource's own blocks)");
    }
}

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
  std::map<std::string, std::string> mappedFrom = mappingsByTarget(sys);
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
