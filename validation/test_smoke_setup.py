"""Smoke tier: the set-up gives working scotch and metis decompositions
(Debian ships stubs; etc/bootstrap builds the real ones) and MPI runs."""
import pytest

from conftest import executable, run

pytestmark = pytest.mark.smoke

BLOCKMESH = """FoamFile { version 2.0; format ascii; class dictionary;
object blockMeshDict; }
convertToMeters 1;
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 0.1) (1 0 0.1) (1 1 0.1)
          (0 1 0.1));
blocks (hex (0 1 2 3 4 5 6 7) (20 20 1) simpleGrading (1 1 1));
boundary ( walls { type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4)
(3 7 6 2)); } frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); } );
"""

CONTROL = """FoamFile { version 2.0; format ascii; class dictionary;
object controlDict; }
application checkMesh; startFrom startTime; startTime 0; stopAt endTime;
endTime 1; deltaT 1; writeControl timeStep; writeInterval 1;
"""

SCHEMES = """FoamFile { version 2.0; format ascii; class dictionary;
object fvSchemes; }
ddtSchemes {} gradSchemes {} divSchemes {} laplacianSchemes {}
interpolationSchemes {} snGradSchemes {}
"""

SOLUTION = """FoamFile { version 2.0; format ascii; class dictionary;
object fvSolution; }
"""


def decompose_dict(method):
    return ("FoamFile { version 2.0; format ascii; class dictionary;"
            f" object decomposeParDict; }}\nnumberOfSubdomains 2;\n"
            f"method {method};\n")


@pytest.mark.parametrize("method", ["scotch", "metis"])
def test_decompose_and_run_parallel(foam_env, tmp_path, method):
    case = tmp_path / method
    (case / "system").mkdir(parents=True)
    (case / "system" / "blockMeshDict").write_text(BLOCKMESH)
    (case / "system" / "controlDict").write_text(CONTROL)
    (case / "system" / "fvSchemes").write_text(SCHEMES)
    (case / "system" / "fvSolution").write_text(SOLUTION)
    (case / "system" / "decomposeParDict").write_text(decompose_dict(method))

    proc = run([executable("blockMesh")], cwd=case)
    assert proc.returncode == 0, proc.stdout + proc.stderr

    proc = run([executable("decomposePar")], cwd=case)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out
    assert "without the " not in out, out
    for rank in (0, 1):
        owner = case / f"processor{rank}" / "constant" / "polyMesh" / "owner"
        assert owner.is_file(), f"decomposePar wrote no {owner}"
    # A balanced split of 400 cells: each rank holds 200 +- 10
    cells = [int(line.split()[-1]) for line in out.splitlines()
             if line.strip().startswith("Number of cells =")]
    assert len(cells) == 2 and abs(cells[0] - cells[1]) <= 20, out

    proc = run(["mpirun", "-np", "2", executable("checkMesh"), "-parallel"],
               cwd=case)
    out = proc.stdout + proc.stderr
    assert proc.returncode == 0, out
    assert "Mesh OK." in out, out
