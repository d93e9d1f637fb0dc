#!/usr/bin/env python3
"""Explore an SMV model explicitly: the second opinion on `emit --to smv`.

NuSMV and nuXmv are not in Debian's archive, so this script reads the part
of the SMV language netlift writes (one MODULE main; VAR and IVAR of
boolean, integer range and enumeration types; DEFINE; ASSIGN init/next;
TRANS; INVARSPEC; CTLSPEC) and the parts fb2smv writes besides (modules
with parameters, instantiated by VAR and flattened here; dotted names;
invariant assignments `x := e`; FAIRNESS and LTLSPEC, which are not
checked; variables without init() or next() take any value of their type,
as in SMV) and computes what SMV's semantics gives it,
independently of netlift's engine: the reachable states (valuations of the
VARs), the transitions (pairs of states related by some valuation of the
IVARs that TRANS allows), the verdict of every INVARSPEC and CTLSPEC in
the initial state (in file order). Input variables are chosen lazily: an evaluation that
reads one not chosen yet is restarted once per value of it, so only the
inputs that matter are enumerated.

Usage: smv-explore.py FILE.smv [--count DEFINE] [--project EXPR,...] [--json]
(--project: the changes of these expressions' values along the
transitions, as pairs of value tuples, stuttering left out)
"""
import argparse
import json
import re
import sys
from collections import deque

TOKEN = re.compile(r"\s*(?:(--[^\n]*)|([A-Za-z_][A-Za-z0-9_$#]*)|(\d+)|"
                   r"(:=|->|<->|!=|<=|>=|\.\.|[.()\[\]{};:,=<>+\-*/!&|?]))")
SECTIONS = {"MODULE", "VAR", "IVAR", "DEFINE", "ASSIGN", "TRANS", "INIT",
            "INVARSPEC", "CTLSPEC", "INVAR", "FAIRNESS", "LTLSPEC"}


class SmvError(Exception):
    pass


def tokenize(text):
    out, pos = [], 0
    while pos < len(text):
        m = TOKEN.match(text, pos)
        if not m:
            if text[pos:].strip() == "":
                break
            line = text.count("\n", 0, pos) + 1
            raise SmvError(f"line {line}: unexpected {text[pos:pos + 10]!r}")
        pos = m.end()
        if m.group(1):
            continue
        tok = m.group(2) or m.group(3) or m.group(4)
        if tok is None:
            continue
        out.append(int(tok) if m.group(3) else tok)
    return out


class Parser:
    def __init__(self, toks):
        self.toks, self.i = toks, 0

    def peek(self, k=0):
        j = self.i + k
        return self.toks[j] if j < len(self.toks) else None

    def next(self):
        t = self.peek()
        self.i += 1
        return t

    def expect(self, t):
        got = self.next()
        if got != t:
            raise SmvError(f"expected {t!r}, got {got!r} at token {self.i}")

    # Expressions, loosest first: -> <-> ?: (| xor) & comparisons + - * / mod
    def expr(self):
        lhs = self.iff()
        if self.peek() == "->":
            self.next()
            return ("->", lhs, self.expr())
        return lhs

    def iff(self):
        lhs = self.cond()
        while self.peek() == "<->":
            self.next()
            lhs = ("<->", lhs, self.cond())
        return lhs

    def cond(self):
        c = self.disj()
        if self.peek() == "?":
            self.next()
            a = self.cond()
            self.expect(":")
            b = self.cond()
            return ("?", c, a, b)
        return c

    def disj(self):
        lhs = self.conj()
        while self.peek() in ("|", "xor"):
            op = self.next()
            lhs = (op, lhs, self.conj())
        return lhs

    def conj(self):
        lhs = self.comparison()
        while self.peek() == "&":
            self.next()
            lhs = ("&", lhs, self.comparison())
        return lhs

    def comparison(self):
        lhs = self.additive()
        while self.peek() in ("=", "!=", "<", ">", "<=", ">="):
            op = self.next()
            lhs = (op, lhs, self.additive())
        return lhs

    def additive(self):
        lhs = self.multiplicative()
        while self.peek() in ("+", "-"):
            op = self.next()
            lhs = (op, lhs, self.multiplicative())
        return lhs

    def multiplicative(self):
        lhs = self.unary()
        while self.peek() in ("*", "/", "mod"):
            op = self.next()
            lhs = (op, lhs, self.unary())
        return lhs

    def unary(self):
        t = self.peek()
        if t == "!":
            self.next()
            return ("!", self.unary())
        if t == "-":
            self.next()
            return ("neg", self.unary())
        if t in ("EX", "AX", "EF", "AF", "EG", "AG"):
            self.next()
            return (t, self.unary())
        if t in ("A", "E") and self.peek(1) == "[":
            self.next()
            self.next()
            p = self.expr()
            self.expect("U")
            q = self.expr()
            self.expect("]")
            return (t + "U", p, q)
        return self.primary()

    def primary(self):
        t = self.next()
        if isinstance(t, int):
            return ("const", t)
        if t == "TRUE":
            return ("const", True)
        if t == "FALSE":
            return ("const", False)
        if t == "(":
            e = self.expr()
            self.expect(")")
            return e
        if t == "case":
            arms = []
            while self.peek() != "esac":
                c = self.expr()
                self.expect(":")
                v = self.expr()
                self.expect(";")
                arms.append((c, v))
            self.next()
            return ("case", arms)
        if isinstance(t, str) and re.match(r"[A-Za-z_]", t):
            return ("id", self.dotted(t))
        raise SmvError(f"unexpected {t!r} at token {self.i}")

    def dotted(self, name):
        """`a.b.c`: a name in an instance, kept as one identifier."""
        while self.peek() == "." and isinstance(self.peek(1), str):
            self.next()
            name += "." + self.next()
        return name

    def type_(self):
        t = self.next()
        if t == "boolean":
            return [False, True]
        if isinstance(t, str) and re.match(r"[A-Za-z_]", t):
            # An instance of module t.
            args = []
            if self.peek() == "(":
                self.next()
                while self.peek() != ")":
                    args.append(self.expr())
                    if self.peek() == ",":
                        self.next()
                self.next()
            return ("module", t, args)
        if t == "{":
            vals = [self.next()]
            while self.peek() == ",":
                self.next()
                vals.append(self.next())
            self.expect("}")
            return vals
        neg = t == "-"
        lo = -self.next() if neg else t
        self.expect("..")
        t = self.next()
        hi = -self.next() if t == "-" else t
        return list(range(lo, hi + 1))

    def modules(self):
        """Every MODULE: its parameters and sections."""
        mods, m = {}, None
        while self.peek() is not None:
            sec = self.next()
            if sec == "MODULE":
                name = self.next()
                params = []
                if self.peek() == "(":
                    self.next()
                    while self.peek() != ")":
                        params.append(self.next())
                        if self.peek() == ",":
                            self.next()
                    self.next()
                m = {"params": params, "vars": {}, "ivars": {},
                     "defines": {}, "init": {}, "next": {}, "assign": {},
                     "trans": [], "specs": []}
                mods[name] = m
            elif m is None:
                raise SmvError(f"{sec!r} before the first MODULE")
            elif sec in ("VAR", "IVAR"):
                table = m["vars"] if sec == "VAR" else m["ivars"]
                while self.peek() not in SECTIONS and self.peek() is not None:
                    name = self.next()
                    self.expect(":")
                    table[name] = self.type_()
                    self.expect(";")
            elif sec == "DEFINE":
                while self.peek() not in SECTIONS and self.peek() is not None:
                    name = self.dotted(self.next())
                    self.expect(":=")
                    m["defines"][name] = self.expr()
                    self.expect(";")
            elif sec == "ASSIGN":
                while self.peek() not in SECTIONS and self.peek() is not None:
                    kind = self.next()
                    if kind in ("init", "next") and self.peek() == "(":
                        self.next()
                        name = self.dotted(self.next())
                        self.expect(")")
                    else:
                        kind, name = "assign", self.dotted(kind)
                    self.expect(":=")
                    m[kind][name] = self.expr()
                    self.expect(";")
            elif sec in ("TRANS", "INVARSPEC", "CTLSPEC"):
                e = self.expr()
                if self.peek() == ";":
                    self.next()
                if sec == "TRANS":
                    m["trans"].append(e)
                else:
                    m["specs"].append((sec, e))
            elif sec in ("FAIRNESS", "LTLSPEC"):
                # Not checked: skipped up to the next section.
                while self.peek() not in SECTIONS and self.peek() is not None:
                    self.next()
            else:
                raise SmvError(f"section {sec!r} is not read")
        return mods

    def model(self):
        return flatten(self.modules())


def rename(e, scope):
    """Expression `e` of a module instance in the flat model's names."""
    prefix, params, local = scope
    op = e[0]
    if op == "const":
        return e
    if op == "id":
        head, _, rest = e[1].partition(".")
        if head in params:
            bound = params[head]
            if not rest:
                return bound
            if bound[0] != "id":
                raise SmvError(f"{e[1]}: parameter {head} is not a name")
            return ("id", bound[1] + "." + rest)
        if head in local:
            return ("id", prefix + e[1])
        return e  # an enumeration constant
    if op == "case":
        return ("case", [(rename(c, scope), rename(v, scope))
                         for c, v in e[1]])
    return (op,) + tuple(rename(x, scope) for x in e[1:])


def flatten(mods):
    """The instance tree from MODULE main as one module (fb2smv's models
    pass variables of the enclosing instance as parameters and assign
    them)."""
    if "main" not in mods:
        raise SmvError("no MODULE main")
    out = {"vars": {}, "ivars": {}, "defines": {}, "init": {}, "next": {},
           "trans": [], "specs": []}
    assign = {}

    def instantiate(name, prefix, params, depth):
        if depth > 50:
            raise SmvError("modules instantiate themselves")
        m = mods.get(name)
        if m is None:
            raise SmvError(f"no MODULE {name}")
        local = set(m["vars"]) | set(m["ivars"]) | set(m["defines"])
        scope = (prefix, params, local)

        def target(n):
            t = rename(("id", n), scope)
            if t[0] != "id":
                raise SmvError(f"{prefix}{n}: assigned parameter is not a "
                               "variable")
            return t[1]
        for v, ty in m["vars"].items():
            if isinstance(ty, tuple):
                sub = mods.get(ty[1])
                if sub is None:
                    raise SmvError(f"no MODULE {ty[1]}")
                if len(sub["params"]) != len(ty[2]):
                    raise SmvError(f"{prefix}{v}: {ty[1]} takes "
                                   f"{len(sub['params'])} parameters")
                instantiate(ty[1], prefix + v + ".",
                            {p: rename(a, scope)
                             for p, a in zip(sub["params"], ty[2])},
                            depth + 1)
            else:
                out["vars"][prefix + v] = ty
        for v, ty in m["ivars"].items():
            out["ivars"][prefix + v] = ty
        for d, e in m["defines"].items():
            out["defines"][prefix + d] = rename(e, scope)
        for kind, table in (("init", out["init"]), ("next", out["next"]),
                            ("assign", assign)):
            for n, e in m[kind].items():
                t = target(n)
                if t in table:
                    raise SmvError(f"{kind}({t}) is assigned twice")
                table[t] = rename(e, scope)
        out["trans"] += [rename(e, scope) for e in m["trans"]]
        out["specs"] += [(k, rename(e, scope)) for k, e in m["specs"]]

    if mods["main"]["params"]:
        raise SmvError("MODULE main has parameters")
    instantiate("main", "", {}, 0)
    # `x := e` makes x a name for e in every state.
    for n, e in assign.items():
        if n not in out["vars"]:
            raise SmvError(f"{n} := ...: not a variable")
        del out["vars"][n]
        out["defines"][n] = e
    return out


class Need(Exception):
    def __init__(self, var):
        self.var = var


def cdiv(a, b):
    q = abs(a) // abs(b)
    return q if (a >= 0) == (b >= 0) else -q


class Evaluator:
    def __init__(self, model):
        self.m = model
        self.enum_consts = {v for dom in list(model["vars"].values()) +
                            list(model["ivars"].values())
                            for v in dom if isinstance(v, str)}

    def eval(self, e, state, ivars, cache):
        op = e[0]
        if op == "const":
            return e[1]
        if op == "id":
            n = e[1]
            if n in state:
                return state[n]
            if n in self.m["ivars"]:
                if n not in ivars:
                    raise Need(n)
                return ivars[n]
            if n in self.m["defines"]:
                if n not in cache:
                    cache[n] = self.eval(self.m["defines"][n], state, ivars,
                                         cache)
                return cache[n]
            if n in self.enum_consts:
                return n
            raise SmvError(f"unknown identifier {n!r}")
        ev = lambda x: self.eval(x, state, ivars, cache)
        if op == "&":
            return ev(e[1]) and ev(e[2])
        if op == "|":
            return ev(e[1]) or ev(e[2])
        if op == "->":
            return (not ev(e[1])) or ev(e[2])
        if op == "?":
            return ev(e[2]) if ev(e[1]) else ev(e[3])
        if op == "case":
            for c, v in e[1]:
                if ev(c):
                    return ev(v)
            raise SmvError("case without a true condition")
        if op == "!":
            return not ev(e[1])
        if op == "neg":
            return -ev(e[1])
        a, b = ev(e[1]), ev(e[2])
        if op in ("=", "!=") and type(a) is not type(b) and \
                (isinstance(a, bool) or isinstance(b, bool)):
            raise SmvError(f"comparing {a!r} with {b!r}: types differ")
        if op == "xor":
            return a != b
        if op == "<->":
            return a == b
        if op == "=":
            return a == b
        if op == "!=":
            return a != b
        if op == "<":
            return a < b
        if op == ">":
            return a > b
        if op == "<=":
            return a <= b
        if op == ">=":
            return a >= b
        if op == "+":
            return a + b
        if op == "-":
            return a - b
        if op == "*":
            return a * b
        if op == "/":
            return cdiv(a, b)
        if op == "mod":
            return a - b * cdiv(a, b)
        raise SmvError(f"operator {op!r} is not evaluated")


def explore(model, max_states):
    ev = Evaluator(model)
    names = list(model["vars"])
    # A variable without init() starts with any value of its type, one
    # without next() takes any value at every step (SMV's semantics).
    inits = [{}]
    for n in names:
        if n not in model["init"]:
            inits = [{**i, n: v} for i in inits for v in model["vars"][n]]

    class Initial(dict):
        """Initial values computed on demand: init() may read others."""
        def __contains__(self, n):
            return n in model["vars"]

        def __missing__(self, n):
            self[n] = None  # a cycle reads None and fails below
            v = ev.eval(model["init"][n], self, {}, {})
            if v not in model["vars"][n]:
                raise SmvError(f"init({n}) = {v} is outside its type")
            self[n] = v
            return v
    inits = [Initial(i) for i in inits]
    for i in inits:
        for n in names:
            i[n]
    trans = model["trans"]

    def successors(state):
        found = set()
        work = [{}]
        while work:
            iv = work.pop()
            cache = {}
            try:
                if not all(ev.eval(t, state, iv, cache) for t in trans):
                    continue
                nxt = [[]]
                for n in names:
                    if n not in model["next"]:
                        nxt = [t + [v] for t in nxt for v in model["vars"][n]]
                        continue
                    v = ev.eval(model["next"][n], state, iv, cache)
                    if v not in model["vars"][n]:
                        raise SmvError(f"next({n}) = {v} is outside its "
                                       f"type in state {state}")
                    for t in nxt:
                        t.append(v)
                found.update(tuple(t) for t in nxt)
            except Need as need:
                for val in model["ivars"][need.var]:
                    work.append({**iv, need.var: val})
        return found

    starts = sorted({tuple(i[n] for n in names) for i in inits}, key=repr)
    index = {t: k for k, t in enumerate(starts)}
    states, succ = list(starts), []
    queue = deque(starts)
    while queue:
        s = queue.popleft()
        out = []
        for t in sorted(successors(dict(zip(names, s))), key=repr):
            if t not in index:
                if len(states) >= max_states:
                    raise SmvError(f"over {max_states} states")
                index[t] = len(states)
                states.append(t)
                queue.append(t)
            out.append(index[t])
        succ.append(out)
    return names, states, succ, ev


def ctl_sets(e, graph):
    """The set of states satisfying CTL formula `e`."""
    names, states, succ, ev = graph
    n = len(states)
    pred = [[] for _ in range(n)]
    for s, out in enumerate(succ):
        for t in out:
            pred[t].append(s)
    every = set(range(n))

    def ex(x):
        return {s for s in range(n) if any(t in x for t in succ[s])}

    def eu(p, q):
        res, work = set(q), list(q)
        while work:
            t = work.pop()
            for s in pred[t]:
                if s not in res and s in p:
                    res.add(s)
                    work.append(s)
        return res

    def eg(p):
        res = set(p)
        while True:
            keep = {s for s in res if any(t in res for t in succ[s])}
            if keep == res:
                return res
            res = keep

    def sat(e):
        op = e[0]
        if op in ("EX", "AX", "EF", "AF", "EG", "AG"):
            x = sat(e[1])
            return {"EX": lambda: ex(x),
                    "AX": lambda: every - ex(every - x),
                    "EF": lambda: eu(every, x),
                    "AF": lambda: every - eg(every - x),
                    "EG": lambda: eg(x),
                    "AG": lambda: every - eu(every, every - x)}[op]()
        if op == "EU":
            return eu(sat(e[1]), sat(e[2]))
        if op == "AU":
            p, q = sat(e[1]), sat(e[2])
            notq = every - q
            return every - (eu(notq, notq - p) | eg(notq))
        if op == "!":
            return every - sat(e[1])
        if op in ("&", "|", "->"):
            a, b = sat(e[1]), sat(e[2])
            return a & b if op == "&" else a | b if op == "|" else \
                (every - a) | b
        return {s for s in range(n)
                if ev.eval(e, dict(zip(names, states[s])), {}, {})}

    return sat(e)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file")
    ap.add_argument("--count", action="append", default=[],
                    help="also count the states where this DEFINE holds")
    ap.add_argument("--max-states", type=int, default=200000)
    ap.add_argument("--project", default=None,
                    help="comma-separated expressions: print the changes "
                    "of their values along the transitions")
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    try:
        model = Parser(tokenize(open(args.file).read())).model()
        graph = explore(model, args.max_states)
        names, states, succ, ev = graph
        result = {"states": len(states),
                  "transitions": sum(len(o) for o in succ)}
        if args.project:
            exprs = [Parser(tokenize(x)).expr()
                     for x in args.project.split(",")]
            values = [tuple(ev.eval(x, dict(zip(names, st)), {}, {})
                            for x in exprs) for st in states]
            result["changes"] = sorted(
                {(values[a], values[b]) for a, out in enumerate(succ)
                 for b in out if values[a] != values[b]}, key=repr)
        for d in args.count:
            result[d] = sum(
                1 for s in states
                if ev.eval(("id", d), dict(zip(names, s)), {}, {}))
        # Every INVARSPEC and CTLSPEC in file order: an invariant holds in
        # every reachable state, a CTL formula in the initial state.
        result["specs"] = [
            all(ev.eval(e, dict(zip(names, s)), {}, {}) for s in states)
            if kind == "INVARSPEC" else 0 in ctl_sets(e, graph)
            for kind, e in model["specs"]]
    except SmvError as e:
        print(f"smv-explore: error: {e}", file=sys.stderr)
        return 1
    if args.json:
        print(json.dumps(result))
    else:
        for k, v in result.items():
            if k == "changes":
                v = "\n".join(f"  {a} -> {b}" for a, b in v)
                print(f"{k}:\n{v}")
                continue
            if isinstance(v, list):
                v = " ".join("true" if x else "false" for x in v) or "-"
            print(f"{k}: {v}")
    return 0


if __name__ == "__main__":
    # Long conjunctions and chains of DEFINEs nest deeply.
    import threading
    sys.setrecursionlimit(1000000)
    threading.stack_size(512 * 1024 * 1024)
    status = []
    worker = threading.Thread(target=lambda: status.append(main()))
    worker.start()
    worker.join()
    sys.exit(status[0] if status else 1)
