# Group medians of a compare-reuse JSON over the measured frames only (frames marked warmup left out).
import json, statistics, sys
G = {'ao': ['ao_position_chain', 'ssao', 'ssao_refresh', 'blur'], 'shadow': ['shadow', 'shadow_refresh'],
     'indirect': ['indirect_gather', 'indirect_upsample', 'indirect_fixup', 'indirect_refresh'],
     'reproject': ['reproject'], 'total': None}
for f in sys.argv[1:]:
    d = json.load(open(f))
    row = []
    for g, ps in G.items():
        med = []
        for run in d['runs']:
            v = [sum(ms for n, ms in fr['passes'].items() if ps is None or n in ps)
                 for fr in run['frames'] if not fr['warmup'] and any(ps is None or n in ps for n in fr['passes'])]
            med.append(statistics.median(v) if v else None)
        old = (d['groups'].get(g) or {}).get('speedup')
        if med[0] and med[1] and old:
            row.append(f"{g} {med[0]:.2f} / {med[1]:.2f} ms: {med[1] / med[0]:.2f}x (was {old:.2f}x)")
    print(f"{f}: " + "; ".join(row))
