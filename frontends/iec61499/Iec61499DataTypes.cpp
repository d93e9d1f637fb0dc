//===- Iec61499DataTypes.cpp - data types and packages --------------------===//
//
// What a 4diac project names types with: packages (`<CompilerInfo
// packageName="mylib::core">`, blocks typed `mylib::core::Counter` or by
// their own name under an `<Import>`), and the data types of `.dtp` files
// (`<DataType>`: structures, arrays, enumerations, subranges, derived
// types), which become ST type declarations for the checker that basic
// FBs' algorithms go through.
//
//===----------------------------------------------------------------------===//
#include "frontends/iec61499/Iec61499Internal.h"

using namespace netlift;
using namespace netlift::iec61499::detail; // and what it uses (plc, llvm)

/// The attribute keeping a type name as written, package included.
static constexpr const char *kQualifiedType = "_netliftQualifiedType";

void Translator::unqualifyTypeNames(pugi::xml_node root) {
  for (pugi::xml_node n = root; n;) {
    for (const char *attr : {"Type", "BaseType"}) {
      pugi::xml_attribute a = n.attribute(attr);
      StringRef name = a.value();
      size_t cut = name.rfind("::");
      if (!a || cut == StringRef::npos)
        continue;
      if (!std::strcmp(attr, "Type"))
        n.append_attribute(kQualifiedType) = a.value();
      std::string own = name.drop_front(cut + 2).str();
      a = own.c_str();
    }
    // Depth first, in document order.
    if (n.first_child())
      n = n.first_child();
    else {
      while (n && n != root && !n.next_sibling())
        n = n.parent();
      if (!n || n == root)
        break;
      n = n.next_sibling();
    }
  }
}

void Translator::checkPackage(pugi::xml_node use, const FbType &t, SMLoc at) {
  StringRef written = use.attribute(kQualifiedType).value();
  if (written.empty() || t.builtin || t.package.empty())
    return;
  StringRef package = written.take_front(written.rfind("::"));
  if (package.equals_insensitive(t.package))
    return;
  diag.error(at, "type '" + written + "' is in package '" + package +
                     "', but the type '" + t.name + "' found is in package '" +
                     t.package + "'");
  diag.note(t.src->locOf(t.root), "the type found");
  throw Failure();
}

void Translator::noteTypeOnlyFile(File &f) {
  pugi::xml_node root = f.doc->document_element();
  StringRef kind = localName(root);
  StringRef name = root.attribute("Name").value();
  SMLoc at = f.src->locOf(root);
  if (kind == "DataType") {
    // Checked as the ST checker checks a TYPE declaration; a structure
    // without members (4diac's template) only where a block uses it.
    pugi::xml_node st = child(root, "StructuredType");
    if (!st || st.first_child())
      useDataType(name, at);
    diag.note(at, "data type '" + name +
                      "' has no behaviour of its own: it is checked, and "
                      "blocks that use it translate with it");
  } else if (kind == "AdapterType") {
    findType(name, at, "adapter"); // registered; its interface is read
    diag.note(at, "adapter type '" + name +
                      "' has no behaviour of its own: blocks use it through "
                      "their plugs and sockets");
  } else if (kind == "AttributeDeclaration") {
    diag.note(at, "attribute type '" + name +
                      "' annotates elements for the IDE; it has no "
                      "behaviour, and netlift reads no attribute it declares");
  } else if (kind == "GlobalConstants") {
    diag.note(at, "global constants '" + name +
                      "' have no behaviour of their own: the algorithms "
                      "that name one of them read its value");
  } else {
    diag.note(at, StringRef(kind).drop_back(4).lower() + " type '" + name +
                      "' describes the runtime platform: netlift runs every "
                      "resource by the execution model chosen with "
                      "--fb-semantics (docs/iec61499.md)");
  }
}

std::vector<std::pair<int64_t, int64_t>>
Translator::arraySize(StringRef written, SMLoc at) {
  // A count (`3`: 0..2), or bounds (`1..3`, `[0..1, 0..2]`).
  StringRef text = written.trim();
  if (text.startswith("[") && text.endswith("]"))
    text = text.drop_front().drop_back();
  llvm::SmallVector<StringRef, 2> dims;
  text.split(dims, ',');
  std::vector<std::pair<int64_t, int64_t>> out;
  for (StringRef dim : dims) {
    auto [lo, hi] = dim.trim().split("..");
    int64_t l = 0, h;
    bool bad = hi.empty() ? lo.trim().getAsInteger(10, h) || (--h, h < 0)
                          : lo.trim().getAsInteger(10, l) ||
                                hi.trim().getAsInteger(10, h) || h < l;
    if (bad)
      fail(at, "ArraySize '" + written +
                   "' is not supported (an element count, or bounds lo..hi; "
                   "arrays of variable length, '*', cannot be modelled)");
    out.push_back({l, h});
  }
  return out;
}

const net::Type *Translator::portType(const Var &v, SMLoc at) {
  pugi::xml_attribute size = v.node.attribute("ArraySize");
  if (elementaryType(v.type) && !size)
    return dataType(v.type, at);
  if (!portTypesKnown && !elementaryType(v.type))
    return nullptr;
  const net::Type *t = nullptr;
  if (elementaryType(v.type))
    t = dataType(v.type, at);
  else
    for (const auto &n : design.types.namedTypes())
      if (n.name.equals_insensitive(v.type))
        t = n.type;
  if (!t)
    fail(at, "port '" + v.name + "' of type " + v.type +
                 ": no block of the translation declares a variable of that "
                 "type, so netlift has no layout for it");
  if (size) {
    auto dims = arraySize(size.value(), at);
    for (size_t i = dims.size(); i-- > 0;)
      t = design.types.getArray(t, dims[i].first, dims[i].second);
  }
  return t;
}

void Translator::resolvePortTypes() {
  portTypesKnown = true;
  for (const PendingPort &p : pendingPorts) {
    net::Module *m = design.lookupModule(p.module);
    net::Port &port = m->ports[m->findPort(p.port)];
    port.type = portType(*p.var, port.loc);
  }
}

TypeSyntax *Translator::typeOf(XmlSource &src, pugi::xml_node decl) {
  SMLoc at = src.locOf(decl);
  auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Named, at);
  ts->name = decl.attribute("Type").value();
  if (ts->name.empty())
    fail(at, "<VarDeclaration> '" + Twine(decl.attribute("Name").value()) +
                 "' without a Type");
  useDataType(ts->name, at);
  if (pugi::xml_attribute size = decl.attribute("ArraySize")) {
    auto *arr = unit.make<TypeSyntax>(TypeSyntaxKind::Array, at);
    for (auto [lo, hi] : arraySize(size.value(), at))
      arr->dims.push_back({intLit(unit, lo, at), intLit(unit, hi, at)});
    arr->elem = ts;
    ts = arr;
  }
  bool found;
  StringRef init = src.placeAttribute(decl, "InitialValue", &found);
  if (found && !init.trim().empty()) {
    ts->init = st::parseStInitializer(init, diag, unit);
    if (!ts->init)
      throw Failure();
    // A duration a block starts with may reach an E_DELAY's DT (a table of
    // delays feeding E_TABLE): it bounds the delays' clocks as a duration
    // parameter does.
    std::function<void(const Initializer *)> durations =
        [&](const Initializer *i) {
          if (i->value && i->value->kind == ExprKind::TimeLit)
            parameterTimes.push_back(i->value->intValue);
          for (const auto &elem : i->elems)
            durations(elem.second);
          for (const auto &field : i->fields)
            durations(field.second);
        };
    durations(ts->init);
  }
  return ts;
}

std::pair<XmlSource *, pugi::xml_node> Translator::findDataType(StringRef name,
                                                                SMLoc at) {
  std::string key = name.upper();
  auto it = dataTypes.find(key);
  if (it == dataTypes.end()) {
    indexLibraries();
    auto path = dataTypeIndex.find(key);
    if (path == dataTypeIndex.end())
      return {nullptr, {}}; // elementary, a block type, or unknown
    File &f = readLibraryFile(path->second, name, at);
    if (localName(f.doc->document_element()) != "DataType")
      return {nullptr, {}};
    registerTypes(f, false);
    it = dataTypes.find(key);
    if (it == dataTypes.end())
      return {nullptr, {}};
  }
  return it->second;
}

void Translator::useDataType(StringRef name, SMLoc at) {
  std::string key = name.upper();
  if (declaredDataTypes.count(key))
    return;
  auto [src, root] = findDataType(name, at);
  if (!src)
    return;
  declaredDataTypes.insert(key);
  auto *td = unit.make<TypeDecl>();
  td->name = root.attribute("Name").value();
  td->loc = src->locOf(root);
  td->type = dataTypeSyntax(*src, root);
  unit.types.push_back(td);
}

/// IEC 61499-2's DataType: one of DirectlyDerivedType, EnumeratedType,
/// SubrangeType, ArrayType, StructuredType.
TypeSyntax *Translator::dataTypeSyntax(XmlSource &src, pugi::xml_node root) {
  SMLoc at = src.locOf(root);
  StringRef name = root.attribute("Name").value();
  auto initOf = [&](pugi::xml_node n, const char *attr, TypeSyntax *ts) {
    bool found;
    StringRef init = src.placeAttribute(n, attr, &found);
    if (found && !init.trim().empty()) {
      ts->init = st::parseStInitializer(init, diag, unit);
      if (!ts->init)
        throw Failure();
    }
    return ts;
  };
  auto named = [&](pugi::xml_node n) {
    StringRef base = n.attribute("BaseType").value();
    if (base.empty())
      fail(src.locOf(n), "<" + localName(n) + "> of data type '" + name +
                             "' without a BaseType");
    useDataType(base, src.locOf(n));
    auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Named, src.locOf(n));
    ts->name = base.str();
    return ts;
  };
  auto bound = [&](pugi::xml_node sub, const char *attr) {
    int64_t v;
    StringRef text = StringRef(sub.attribute(attr).value()).trim();
    if (text.getAsInteger(10, v))
      fail(src.locOf(sub), Twine(attr) + " '" + text + "' of data type '" +
                               name + "' is not an integer");
    return intLit(unit, v, src.locOf(sub));
  };
  for (pugi::xml_node n : root.children()) {
    StringRef kind = localName(n);
    SMLoc loc = src.locOf(n);
    if (kind == "DirectlyDerivedType")
      return initOf(n, "InitialValue", named(n));
    if (kind == "SubrangeType") {
      TypeSyntax *base = named(n);
      auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Subrange, loc);
      ts->name = base->name;
      pugi::xml_node sub = child(n, "Subrange");
      if (!sub)
        fail(loc,
             "<SubrangeType> of data type '" + name + "' without a <Subrange>");
      ts->lo = bound(sub, "LowerLimit");
      ts->hi = bound(sub, "UpperLimit");
      return initOf(n, "InitialValue", ts);
    }
    if (kind == "EnumeratedType") {
      auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Enum, loc);
      for (pugi::xml_node v : n.children("EnumeratedValue"))
        ts->enumerators.push_back(
            {v.attribute("Name").value(), nullptr, src.locOf(v)});
      if (ts->enumerators.empty())
        fail(loc, "enumerated data type '" + name + "' has no values");
      return initOf(n, "InitialValue", ts);
    }
    if (kind == "ArrayType") {
      auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Array, loc);
      for (pugi::xml_node sub : n.children("Subrange"))
        ts->dims.push_back(
            {bound(sub, "LowerLimit"), bound(sub, "UpperLimit")});
      if (ts->dims.empty())
        fail(loc, "array data type '" + name + "' without a <Subrange>");
      ts->elem = named(n);
      return initOf(n, "InitialValues", ts);
    }
    if (kind == "StructuredType") {
      auto *ts = unit.make<TypeSyntax>(TypeSyntaxKind::Struct, loc);
      for (pugi::xml_node m : n.children()) {
        StringRef mk = localName(m);
        if (mk != "VarDeclaration")
          fail(src.locOf(m), "<" + mk + "> in structured data type '" + name +
                                 "' is not supported (members are "
                                 "<VarDeclaration>s)");
        auto *v = unit.make<VarDecl>();
        v->name = m.attribute("Name").value();
        v->loc = src.locOf(m);
        v->section = VarSection::Var;
        if (v->name.empty())
          fail(v->loc, "member of data type '" + name + "' without a Name");
        v->typeSyntax = typeOf(src, m);
        ts->fields.push_back(v);
      }
      if (ts->fields.empty())
        fail(loc, "structured data type '" + name + "' has no members");
      return ts;
    }
  }
  fail(at, "data type '" + name +
               "' is none of DirectlyDerivedType, EnumeratedType, "
               "SubrangeType, ArrayType, StructuredType");
}

/// Each module `Init_<Block>_<input>`: a stored output OUT of the input's
/// type holding what the block's copy of the input starts with (its
/// InitialValue, else its type's), so an unconnected structure or array
/// input reads as in FORTE, where it keeps its initial value.
void Translator::aggregateConstantModules() {
  for (auto &[name, c] : aggregateConstants) {
    const net::Module *block = design.lookupModule(c.type->name);
    const net::Port *port = nullptr;
    if (block)
      for (const net::Port &p : block->ports)
        if (StringRef(p.name).equals_insensitive(c.input))
          port = &p;
    if (!port || !port->type)
      fail(c.loc, "input '" + c.input + "' of '" + c.type->name +
                      "' is unconnected and its type is not one netlift "
                      "can give a constant value");
    net::Expr *init = nullptr;
    bool copied = false;
    std::string copy = "_" + c.input;
    for (const net::Var &v : block->vars)
      if (StringRef(v.name).equals_insensitive(copy) ||
          StringRef(v.name).equals_insensitive(copy + "_")) {
        init = v.init;
        copied = true;
      }
    if (!copied && init == nullptr)
      for (const Var &v : c.type->inputs)
        if (StringRef(v.name).equals_insensitive(c.input) &&
            !StringRef(v.node.attribute("InitialValue").value()).trim().empty())
          fail(c.loc, "unconnected input '" + c.input + "' of '" +
                          c.type->name +
                          "' has a structure or array InitialValue but no "
                          "event samples it (With): not supported");
    const net::Type *type = port->type;
    net::Module *m = b.createModule(name, false, c.loc);
    if (!m)
      fail(c.loc, "a module named '" + name + "' exists already");
    uint32_t p =
        b.addPort("OUT", net::PortKind::Data, net::PortDir::Out, type, c.loc);
    m->ports[p].init = init;
  }
}

void Translator::addGlobalConstants(File &f) {
  // <GlobalConstants><GlobalConstants><VarDeclaration .../>... (the
  // declarations, then the ST source they were written as).
  pugi::xml_node root = f.doc->document_element();
  for (pugi::xml_node list : root.children())
    if (localName(list) == "GlobalConstants")
      for (pugi::xml_node v : list.children())
        if (localName(v) == "VarDeclaration")
          globalConstants[StringRef(v.attribute("Name").value()).upper()]
              .push_back({f.src.get(), v});
}

void Translator::readGlobalConstants() {
  if (globalConstantsRead)
    return;
  globalConstantsRead = true;
  indexLibraries();
  for (const std::string &path : globalConstantFiles)
    addGlobalConstants(readPath(path));
}

void Translator::declareGlobalConstantsUsed(
    FbType &t,
    llvm::function_ref<VarDecl *(StringRef, TypeSyntax *, VarSection, SMLoc)>
        declare) {
  // The words of the algorithms and the transition conditions.
  std::set<std::string> words;
  auto collectWords = [&](StringRef text) {
    for (size_t i = 0; i < text.size();) {
      if (!isalpha(static_cast<unsigned char>(text[i])) && text[i] != '_') {
        ++i;
        continue;
      }
      size_t j = i;
      while (j < text.size() &&
             (isalnum(static_cast<unsigned char>(text[j])) || text[j] == '_'))
        ++j;
      words.insert(text.slice(i, j).upper());
      i = j;
    }
  };
  for (pugi::xml_node a : t.body.children("Algorithm")) {
    pugi::xml_node st = a.child("ST");
    collectWords(st.attribute("Text").value());
    collectWords(st.child_value());
  }
  for (pugi::xml_node tr : child(t.body, "ECC").children("ECTransition"))
    collectWords(tr.attribute("Condition").value());
  if (words.empty())
    return;
  readGlobalConstants();
  for (const auto &[name, decls] : globalConstants) {
    if (!words.count(name) || currentPou->find(name))
      continue;
    const auto &[src, node] = decls.front();
    for (const auto &[otherSrc, other] : decls)
      if (StringRef(other.attribute("Type").value()) !=
              node.attribute("Type").value() ||
          StringRef(other.attribute("InitialValue").value()) !=
              node.attribute("InitialValue").value()) {
        diag.error(t.src->locOf(t.root),
                   "'" + t.name + "' names the global constant '" +
                       node.attribute("Name").value() +
                       "', which two files declare differently");
        diag.note(src->locOf(node), "one declaration");
        diag.note(otherSrc->locOf(other), "the other");
        throw Failure();
      }
    VarDecl *d = declare(node.attribute("Name").value(), typeOf(*src, node),
                         VarSection::Var, src->locOf(node));
    d->constant = true;
  }
}
