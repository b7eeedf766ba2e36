"""The short-name rule of faultmesh's outputs (docs/formats.md, "Names"), written
here from its text, for the checkers: a name's one-token form, cut with a
hash suffix where it is too long or taken."""


KEEP = set(b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789._-")


def token(name):
    """The one-token form of a name (docs/formats.md, "Names"): kept bytes stay,
    each run of others becomes one '_'."""
    b = name.encode("utf-8")
    out = bytearray()
    for i, c in enumerate(b):
        if c in KEEP:
            out.append(c)
        elif i == 0 or b[i - 1] in KEEP:
            out.append(ord("_"))
    return out.decode("ascii") or "_"


def short_names(names, limit):
    """Short names by the rule of docs/formats.md, written here from its text."""
    out = []
    for name in names:
        t = token(name)
        if len(t) > limit or t in out:
            h = 2166136261
            for c in name.encode("utf-8"):
                h = ((h ^ c) * 16777619) & 0xFFFFFFFF
            span = 36 ** 4
            for k in range(span):
                c = (h % span + k) % span
                digits = ""
                for _ in range(4):
                    digits = "0123456789abcdefghijklmnopqrstuvwxyz"[c % 36] + digits
                    c //= 36
                cand = t[:limit - 5] + "~" + digits
                if cand not in out:
                    break
            t = cand
        out.append(t)
    return out
