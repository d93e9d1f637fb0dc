#!/usr/bin/env python3
"""Explore an SMV model explicitly: the second opinion on `emit --to smv`.

NuSMV and nuXmv are not in Debian's archive, so this script reads the part
of the SMV language netlift writes (one MODULE main; VAR and IVAR of
boolean, integer range and enumeration types; DEFINE; ASSIGN init/next;
TRANS; INVARSPEC; CTLSPEC) and computes what SMV's semantics gives it,
independently of netlift's engine: the reachable states (valuations of the
VARs), the transitions (pairs of states related by some valuation of the
IVARs that TRANS allows), the verdict of every INVARSPEC and CTLSPEC in
the initial state (in file order). Input variables are chosen lazily: an evaluation that
reads one not chosen yet is restarted once per value of it, so only the
inputs that matter are enumerated.

Usage: smv-explore.py FILE.smv [--count DEFINE] [--json]
"""
import argparse
import json
import re
import sys
from collections import deque

TOKEN = re.compile(r"\s*(?:(--[^\n]*)|([A-Za-z_][A-Za-z0-9_$#]*)|(\d+)|"
                   r"(:=|->|<->|!=|<=|>=|\.\.|[()\[\]{};:,=<>+\-*/!&|?]))")
SECTIONS = {"MODULE", "VAR", "IVAR", "DEFINE", "ASSIGN", "TRANS", "INIT",
            "INVARSPEC", "CTLSPEC", "INVAR"}


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
            return ("id", t)
        raise SmvError(f"unexpected {t!r} at token {self.i}")

    def type_(self):
        t = self.next()
        if t == "boolean":
            return [False, True]
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

    def model(self):
        m = {"vars": {}, "ivars": {}, "defines": {}, "init": {}, "next": {},
             "trans": [], "specs": []}
        while self.peek() is not None:
            sec = self.next()
            if sec == "MODULE":
                if self.next() != "main":
                    raise SmvError("only MODULE main is read")
            elif sec in ("VAR", "IVAR"):
                table = m["vars"] if sec == "VAR" else m["ivars"]
                while self.peek() not in SECTIONS and self.peek() is not None:
                    name = self.next()
                    self.expect(":")
                    table[name] = self.type_()
                    self.expect(";")
            elif sec == "DEFINE":
                while self.peek() not in SECTIONS and self.peek() is not None:
                    name = self.next()
                    self.expect(":=")
                    m["defines"][name] = self.expr()
                    self.expect(";")
            elif sec == "ASSIGN":
                while self.peek() in ("init", "next"):
                    kind = self.next()
                    self.expect("(")
                    name = self.next()
                    self.expect(")")
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
            else:
                raise SmvError(f"section {sec!r} is not read")
        return m


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
    init = {}
    for n in names:
        if n not in model["init"]:
            raise SmvError(f"{n} has no init()")
        init[n] = ev.eval(model["init"][n], {}, {}, {})
        if init[n] not in model["vars"][n]:
            raise SmvError(f"init({n}) = {init[n]} is outside its type")
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
                nxt = []
                for n in names:
                    v = (ev.eval(model["next"][n], state, iv, cache)
                         if n in model["next"] else state[n])
                    if v not in model["vars"][n]:
                        raise SmvError(f"next({n}) = {v} is outside its "
                                       f"type in state {state}")
                    nxt.append(v)
                found.add(tuple(nxt))
            except Need as need:
                for val in model["ivars"][need.var]:
                    work.append({**iv, need.var: val})
        return found

    start = tuple(init[n] for n in names)
    index = {start: 0}
    states, succ = [start], []
    queue = deque([start])
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
    ap.add_argument("--json", action="store_true")
    args = ap.parse_args()
    try:
        model = Parser(tokenize(open(args.file).read())).model()
        graph = explore(model, args.max_states)
        names, states, succ, ev = graph
        result = {"states": len(states),
                  "transitions": sum(len(o) for o in succ)}
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
