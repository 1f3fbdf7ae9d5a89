"""What every part of the report reads off poundbench's CSV rows: loading them, their
numbers and settings, the label of a solver configuration, and writing a page. No
matplotlib here (figure.py), so that checking README's numbers starts in a blink."""

import csv
import functools
import json
import os
import sys
import types
from collections import defaultdict

# Columns that label a curve of a spectrum (everything that is neither the abscissa nor a result).
CASE_KEYS = ["scene", "pulse", "directivity", "eps", "pi3", "pi5", "pi6", "pi7", "pi8", "xi", "n_free", "a_p", "w_p"]


def load(paths):
    rows = []
    for path in paths:
        with open(path, newline="") as f:
            rows.extend(csv.DictReader(f))
    if not rows:
        sys.exit("make_report.py: no result rows in " + ", ".join(paths))
    return rows


def num(row, key):
    """A column as a float; an empty field (a value that does not exist) is NaN."""
    value = row.get(key, "")
    return float(value) if value not in ("", None) else float("nan")


def unresolved(row):
    """A summary row's runs that finished without resolving what they solved (the
    `unresolved` column, kit/verdict.hpp); 0 in a file from before that column."""
    return int(row.get("unresolved") or 0)


def sound(row):
    """Whether a summary row may be ranked: none of its runs failed, none is unresolved."""
    return int(row["failed"]) == 0 and unresolved(row) == 0


def settings_fields(row):
    """The `settings` column (a JSON object of the solver's named values) as a read-only dict."""
    return _parsed_settings(row["settings"])


@functools.cache
def _parsed_settings(text):
    # A study's rows share a few hundred settings texts: parsing each once took the report's
    # 665 000 calls from 4.2 s of JSON to lookups (profiled on the main job's results).
    return types.MappingProxyType(json.loads(text or "{}"))


def steps_of(row):
    """The run's step count N, or None for a run whose step is set another way (wh) or has none."""
    steps = settings_fields(row).get("steps")
    return None if steps is None else int(steps)


def config_label(row):
    """A solver configuration without its step: one line of a work-precision diagram or a
    stability plot. The full settings of each are in the CSV and the solvers' READMEs."""
    return _config_label(row["solver"], row.get("variant") or "", row["settings"])


# A Python callable's rows name it in their command as this and the name it was given in
# `solvers={"name": f}` (python/poundbench_module.cpp).
CALLABLE_PREFIX = "python "


def external_name(fields):
    """An external solver's name as its user gave it: a `name` of its settings (a name given
    on the command line), a Python callable's key in `solvers=`, else its command itself, so
    that two programs never share a line."""
    if fields.get("name"):
        return str(fields["name"])
    command = str(fields.get("command", ""))
    if command.startswith(CALLABLE_PREFIX) and command[len(CALLABLE_PREFIX):].strip():
        return command[len(CALLABLE_PREFIX):]
    return command or "external"


@functools.cache
def _config_label(solver, variant, settings):
    fields = _parsed_settings(settings)
    label = external_name(fields) if solver == "external" else solver
    if variant:
        label += " " + variant
    if "theta" in fields:  # moreau-jean, and siconos' Moreau-Jean variants
        label += f" theta={fields['theta']}"
    if "steps_per_sample" in fields:  # the step rule `record` (issue 34): h = DT / m, m >= k
        label += f" rule=record k={fields['steps_per_sample']}"
    if "tol_scale" in fields:  # the reference, and siconos' event-driven variant
        label += f" tol_scale={fields['tol_scale']}"
    if "contact" in fields:  # the reference solving a compliant model exactly
        label += f" {fields['contact']}"
    if "integrator" in fields:  # compliant: cvode (its method and rtol) or newmark
        label += f" {fields['integrator']}"
        if fields["integrator"] == "cvode":
            label += f" {fields.get('method', 'bdf')} rtol={fields.get('rtol', 1e-8):g}"
    if "k_contact" in fields:  # compliant elements given in physical units: the stiffness as given
        label += f" k={fields['k_contact']:g} N/m"
    elif "stiffness" in fields:  # compliant elements: the stiffness Pi term
        label += f" K={fields['stiffness']:g}"
    if "contact_steps" in fields:  # mujoco's faithful variants: the contact time constant in steps
        label += f" M={fields['contact_steps']}"
    if fields.get("lcp") == "enum" and not variant.endswith("-enum"):  # siconos, Settings::lcp
        label += " lcp=enum"
    if fields.get("projection_tol", 1e-10) != 1e-10:  # siconos' projections, away from their default
        label += f" projection_tol={fields['projection_tol']}"
    return label


def setting_label(row):
    """A solver configuration with its step: one setting of a study. A step in seconds (h_s: one
    step for every case of a study in physical units) is labelled as such, not by a N."""
    fields = settings_fields(row)
    if "h_s" in fields:
        return config_label(row) + f", h = {fields['h_s']:g} s"
    n = steps_of(row)
    return config_label(row) + ("" if n is None else f", N = {n}")


def median(values):
    """The median of a non-empty list (the mean of the middle two for an even count)."""
    values = sorted(values)
    mid = len(values) // 2
    return values[mid] if len(values) % 2 else 0.5 * (values[mid - 1] + values[mid])


def by_family(rows):
    """The rows of each family, families in the order they first appear: one pass, where a
    scan of every row per family made a report of F families and R rows cost F x R (1,000
    families of a 100,000-row summary: 10^8 comparisons in each of five places)."""
    families = defaultdict(list)
    for r in rows:
        families[r["family"]].append(r)
    return families


def md_text(text):
    """A name (a family, a solver's variant: any text a study's rows hold) as one line of
    markdown: line ends as spaces; backslashes, and the brackets of a link or an image's text,
    escaped."""
    return md_cell(text, "[]")


def md_cell(text, escaped="|"):
    """A name as a cell of a markdown table: one line, its backslashes and '|' escaped ('\\|',
    which GitHub's tables and page.table_html read as the character, not a cell's end)."""
    text = " ".join(str(text).replace("\\", "\\\\").splitlines())
    for c in escaped:
        text = text.replace(c, "\\" + c)
    return text


def write_page(out_dir, lines, script=None):
    """Writes out_dir/README.md through a temporary file, so a failed run leaves the old one,
    and says so on stdout when `script` names the writer."""
    path = os.path.join(out_dir, "README.md")
    with open(path + ".tmp", "w") as f:
        f.write("\n".join(lines))
    os.replace(path + ".tmp", path)
    if script:
        print(f"{script}: wrote {path}")
