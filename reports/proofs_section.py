"""Report section "Proved", from proofs.json (`gomboc prove --json`, saved by verify/s7_proofs.c): each statement
with its result, the enclosures and its CPU time. Kept apart from the findings: a finding is decided by a rule on
estimates with error bars; a statement here is a theorem about the stated system, with the hypotheses it rests on and
which of them are proved."""
import os

from common import load_json, section_start


def interval(pair):
    lo, hi = pair
    return f"[{lo:.17g}, {hi:.17g}]"


def proofs_section(out):
    lines, data = section_start(out, "Proved", "proofs.json",
                                "proofs.json missing: the harness's test 'proofs: gomboc prove' did not write it")
    if data is None:
        return lines
    statements = data["statements"]
    lines += [f"`gomboc prove` on Arb's balls ({data['precision_bits']:g} bits): **{data['proved']:g} of "
              f"{data['attempted']:g} statements attempted proved**. "
              "Nothing here is estimated: each number is an interval rounded outwards from Arb's balls (or from the "
              "certificate's interval arithmetic, checked against Arb), and a statement is proved only when the intervals "
              "decide it (docs/proofs.md). The method's oracles and published results reproduced come first; then the "
              "Gömböcs' reduced models at Table 1's rolling forcing, whose statements are about the Melnikov function of "
              "the reduced model (first order in the forcing): the findings above stand on estimates of the full model.", "",
              "| statement | result | detail |", "|---|---|---|"]
    def cell(text):
        return str(text).replace("|", "\\|")  # |dM/dt0| inside a table cell

    for s in statements:
        lines.append(f"| {cell(s['statement'])} | {cell(s['result'])} | {cell(s.get('summary', s.get('needs', '')))} |")
    lines += [""]
    for s in statements:
        if "theorem" in s and "function" in s:
            lines += [f"**{s['statement']}.** {s['function']}. Method: {s['method']}. Theorem: {s['theorem']}. "
                      f"Hypotheses: {s['hypotheses']}. Reading: {s['reading']}. Zeros of M in t0: "
                      + (", ".join(interval(w) for w in s["zero_t0"]) or "none") + ".", ""]
            break
    first = next((s for s in statements if "enclosures" in s), None)
    if first:
        lines += [f"Enclosures of {first['statement']} ({first['method']}; T = {first['T']:.4g}):", "",
                  "| integral | quadrature | closed form |", "|---|---|---|"]
        for name, e in first["enclosures"].items():
            lines.append(f"| {name} | {interval(e['quadrature'])} | {interval(e['closed_form'])} |")
        lines += ["", "The other statements' enclosures: `gomboc prove --json`.", ""]
    for s in statements:
        if "data" not in s:
            continue
        e, est = s["enclosures"], s["estimates"]
        hyps = "; ".join(f"{h['hypothesis']} ({h['status']})" for h in s["hypotheses"])
        zeros = ", ".join(interval(w) for w in s["zero_t0"]) or "none"
        lines += [f"**{s['statement']}** ({s['result']}; verdict: {s['verdict']}). System: {s['system']}. Function: "
                  f"{s['function']}. Method: {s['method']}. Theorem: {s['theorem']}. Hypotheses: {hyps}. Scope: {s['scope']}. "
                  f"Was: {s['was']}.", "",
                  f"M = {interval(e['M'])}, mu D = {interval(e['mu_D'])}, C1 = {interval(e['C1'])}, S1 = {interval(e['S1'])}, "
                  f"C2 = {interval(e['C2'])}, S2 = {interval(e['S2'])} (today's estimates D {est['D']:.10g}, C1 {est['C1']:.6g}, "
                  f"S1 {est['S1']:.6g}, C2 {est['C2']:.6g}, S2 {est['S2']:.6g}: " + ("inside" if est["inside"] else "NOT inside")
                  + f"); zeros of M in t0: {zeros}; {s['cells']:g} cells of q at resolution {s['resolution']:g}, "
                  f"{s['surface_boxes']:g} surface boxes, {s['seconds']:.3g} s CPU.", ""]
    for s in statements:
        if "boxes" not in s:
            continue
        boxes = "; ".join(f"the box y {interval(b['y'])}, z {interval(b['z'])}: K = {interval(b['K_y'])} x {interval(b['K_z'])} "
                          f"({'inside' if b['proved'] else 'NOT inside'})" for b in s["boxes"])
        lines += [f"**{s['statement']}** ({s['result']}). System: {s['system']}. Reproduces: {s['reproduces']}. Method: "
                  f"{s['method']}. Theorem: {s['theorem']}. {boxes[:1].upper() + boxes[1:]}. Period {interval(s['period'])} "
                  f"({s['seconds']:.3g} s CPU).", ""]
    for s in statements:
        if "h_sets" not in s:
            continue
        edges = "; ".join(f"U{i} = {interval(h['u'])}: its edges return to {interval(h['image_of_low_edge_u'])} and "
                          f"{interval(h['image_of_high_edge_u'])}, covers {h['covers']}" for i, h in enumerate(s["h_sets"]))
        k = int(s.get("iterates", 1))
        per_map = (f" for the map iterated {k} times, so h_top >= {s['entropy_lower_bound_map']:.17g} for the map itself"
                   if k > 1 and "entropy_lower_bound_map" in s else "")
        trap = (f" The trapping rectangle's returns: across {interval(s['trap_image_u'])}, along {interval(s['trap_image_s'])}."
                if "trap_image_u" in s else "")
        lines += [f"**{s['statement']}** ({s['result']}). System: {s['system']}. Sets: {s['sets']}. Reproduces: "
                  f"{s['reproduces']}. Method: {s['method']}. Theorem: {s['theorem']}. Reading: {s['reading']}.{trap} "
                  f"Edges: {edges}. h_top >= {s['entropy_lower_bound']:.17g}{per_map} ({s['seconds']:.3g} s CPU).", ""]
    for s in statements:
        if "strips" not in s:
            continue
        strips = "; ".join(f"U{i} = {interval(h['u'])} in {h['returns']:g}"
                           + (f" across its reach {interval(h['reach'])} ({h['targets']:g} strips in it)" if "reach" in h else "")
                           + f": its edges to {interval(h['image_of_low_edge_u'])} and "
                           f"{interval(h['image_of_high_edge_u'])}" + ("" if h["across"] else " (NOT proved)")
                           for i, h in enumerate(s["strips"]))
        lines += [f"**{s['statement']}** ({s['result']}). System: {s['system']}. Sets: {s['sets']}. Reproduces: "
                  f"{s['reproduces']}. Method: {s['method']}. Theorem: {s['theorem']}. Reading: {s['reading']}. "
                  f"Strips: {strips}. h_top >= {s['entropy_lower_bound']:.17g} ({s['seconds']:.3g} s CPU).", ""]
    for s in statements:
        if "strip_count" not in s:
            continue
        lines += [f"**{s['statement']}** ({s['result']}). System: {s['system']}. Sets: {s['sets']}. Method: "
                  f"{s['method']}. Theorem: {s['theorem']}. Reading: {s['reading']}. h_top >= {s['bound']:.17g} "
                  f"(the claim {s['claim']:g}; {s['seconds']:.3g} s CPU).", ""]
    for s in statements:
        if "index_pair" not in s:
            continue
        pair = s["index_pair"]
        conditions = ", ".join(f"{name.replace('_', ' ')} {'proved' if pair[name] else 'NOT proved'}"
                               for name in ("positively_invariant", "exit_set", "isolated"))
        lines += [f"**{s['statement']}** ({s['result']}). System: {s['system']}. Sets: {s['sets']}. Reproduces: "
                  f"{s['reproduces']}. Method: {s['method']}. Theorem: {s['theorem']}. Reading: {s['reading']}. "
                  f"Index pair: {conditions} ({pair['invariant_boxes']:g} boxes on bi-infinite paths inside P1 \\ P0). "
                  f"H_*(P1, P0; Z2) of ranks {s['h0']:g}, {s['h1']:g}, {s['h2']:g}; {s['regions']:g} regions "
                  f"({s['regions_used']:g} used); the sofic graph {s['symbols']:g} symbols and {s['transitions']:g} "
                  f"transitions, its largest component {s['component']:g}, rho >= {s['rho_lower_bound']:.12g}; "
                  f"h_top >= {s['entropy_lower_bound']:.17g} ({s['seconds']:.3g} s CPU).", ""]
    lines += horseshoe_lines(out)
    return lines


def horseshoe_lines(out):
    """The Gömböcs' horseshoes: `make prove` alone proves all their links (minutes); make verify's harness proves
    three of Gömböc II's."""
    path = os.path.join(out, "proof-horseshoe.json")
    if not os.path.exists(path):
        return ["Gömböc II's horseshoe along a homoclinic orbit (`gomboc prove --horseshoe`) takes minutes: `make prove` "
                "proves it and writes reports/out/proof-horseshoe.json, which this section then shows; `make verify` "
                "proves Gömböc II's three covering relations by the saddle, its sets' disjointness and its entropy bound "
                "(the harness's suite on it).", ""]
    lines = []
    for s in load_json(path)["statements"]:
        hyps = "; ".join(f"{h['hypothesis']} ({h['status']})" for h in s["hypotheses"])
        links = ", ".join(f"{l['link']}" + (f" across the tie {interval(l['tie'])}" if "tie" in l else "")
                          + (f" (strip {l['strip_margin']:.3f}, edges {l['edge_margin']:.3f})" if l["covers"]
                             else f" (NOT proved: {l['failure']})") for l in s["links"])
        lines += [f"**{s['statement']}** ({s['result']}; `make prove`, reports/out/proof-horseshoe.json). System: "
                  f"{s['system']}. Sets: {s['sets']}. Method: {s['method']}. Theorem: {s['theorem']}. Hypotheses: {hyps}. "
                  f"Links, with the margins proved (of the target's half-widths): {links}. ln rho >= {s['log_rho']:.17g} "
                  f"({s['seconds']:.4g} s CPU).", ""]
    return lines
