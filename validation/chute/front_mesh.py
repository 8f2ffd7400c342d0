"""Figure 5 against the mesh along the slope: the chute tutorial with nx
columns (default 155, 4 mm; 620, 1 mm), continued in the moving frame from
8 s to 14 s, and with d = 0.143 mm on 1 mm columns from 4 s to 14 s (as
grain_size.py on 4 mm), each front against (5.17) for chi = 1 and 5/4: xi
where h reaches 1/2 and 0.9 of h_inf (grain_size.front).  Tells whether
the lag of the computed front behind (5.17) is the mesh's.

    /usr/bin/python3 validation/chute/front_mesh.py CASE [CASE ...] [--out DIR]

writes DIR/front_mesh.json and DIR/figure5_d<d>_nx<nx>.png (DIR default
validation/chute/measured); set-up in SETUP.
"""
import argparse
import json
from pathlib import Path

from granularfoam.post import chute
from grain_size import PISO_SETTING, front

SETUP = ("for NX in 155 620; do cp -r tutorials/chute chute_nx$NX && "
         "(cd chute_nx$NX && ./Allrun -serial " + PISO_SETTING + " -nx $NX "
         "-endTime 8 -writeInterval 1 && ./Allrun-movingFrame); done; cp -r "
         "tutorials/chute chute_d143_nx800 && (cd chute_d143_nx800 && "
         "./Allrun -np 2 " + PISO_SETTING + " -d 143e-6 -Lx 0.8 -nx 800 -endTime 4 "
         "-writeInterval 0.5 && ./Allrun-movingFrame -start 4 -endTime 14 "
         "-parallel)")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cases", nargs="+", type=Path)
    parser.add_argument("--out", type=Path, default=Path(__file__).resolve()
                        .parent / "measured")
    args = parser.parse_args(argv)
    runs = {}
    for case in args.cases:
        par = chute.parameters(case)
        d = chute.grain_diameter(case)
        key = f"d{d * 1e6:.0f}um_nx{int(par['nx'])}"
        res = front(case, args.out / f"figure5_{key}.png")
        res["dx_m"] = par["Lx"] / par["nx"]
        res["d_m"] = d
        runs[key] = res
    result = {"runs": runs, "setup": SETUP,
              "command": "/usr/bin/python3 validation/chute/front_mesh.py "
                         + " ".join(c.name for c in args.cases)}
    path = args.out / "front_mesh.json"
    path.write_text(json.dumps(result, indent=2) + "\n")
    print(json.dumps(result, indent=2))


if __name__ == "__main__":
    main()
