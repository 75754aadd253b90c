"""Markdown helpers shared by the seed sections' reports (scripts/bench_*.py)."""


def num(v, digits=1):
    """A number for a table cell: '–' when missing, thousands separated from 1,000 on."""
    if v is None:
        return "–"
    if isinstance(v, float) and abs(v) >= 1000:
        return f"{v:,.0f}"
    if isinstance(v, int):
        return f"{v:,}"
    return f"{v:.{digits}f}"


def md_table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(lines)


def result(rec):
    """A run record's passtrace JSON, or None when the run failed or did not run."""
    return rec["result"] if rec and rec.get("status") == "ok" else None


def field(r, *names):
    """The first of `names` present in a run's JSON (flat keys, or the `structure` object)."""
    for n in names:
        if r is None:
            return None
        if n in r:
            return r[n]
        if isinstance(r.get("structure"), dict) and n in r["structure"]:
            return r["structure"][n]
    return None


def verdict(holds):
    return "**holds**" if holds else "**does not hold**"
