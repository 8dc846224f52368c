"""scripts/uintah_decks.py: R_Tester lists read with their modUPS/modUPS2 edits, as Uintah's
helpers/modUPS.py makes them (a sed of the line holding a tag; xmlstarlet XPath update/delete)."""
from tests.conftest import load_script

ud = load_script("uintah_decks")

DECK = b"""<?xml version="1.0"?>
<Uintah_specification>
  <Time>
    <maxTime>  1.0  </maxTime>
    <max_Timesteps>50</max_Timesteps>
  </Time>
  <DataArchiver><filebase>a.uda</filebase><outputInterval>0.1</outputInterval></DataArchiver>
  <Grid><BoundaryConditions><Face side="x-"><BCType id="0" label="Velocity" var="Dirichlet"/></Face></BoundaryConditions>
  <Level><Box label="1"><patches>[1,1,1]</patches></Box></Level></Grid>
  <DataAnalysis><Module name="minMax"/></DataAnalysis>
</Uintah_specification>
"""
LIST = '''
from helpers.runSusTests_git import runSusTests, getInputsDir
from helpers.modUPS import modUPS, modUPS2
the_dir = "%s/%s" % (getInputsDir(), "ICE")
short = modUPS(the_dir, "d.ups", ["<maxTime> 0.0001 </maxTime>"])
edited = modUPS2(the_dir, "d.ups", [("update", "/Uintah_specification/Grid/BoundaryConditions/Face[@side='x-']/BCType[@id='0' and @label='Velocity']/@var :powerLawProfile"),
                                    ("delete", "/Uintah_specification/DataAnalysis")])
NIGHTLYTESTS = [("plain", "d.ups", 1, "All", ["exactComparison"]), ("short", short, 2, "All", [])]
OTHER = [("edited", edited, 8, "All", []), ("plain", "d.ups", 1, "All", [])]
'''


def test_lists_and_edits(tmp_path):
    (tmp_path / "R_Tester").mkdir()
    (tmp_path / "R_Tester" / "ICE.py").write_text(LIST)
    (tmp_path / "StandAlone" / "inputs" / "ICE").mkdir(parents=True)
    (tmp_path / "StandAlone" / "inputs" / "ICE" / "d.ups").write_bytes(DECK)
    tests = ud.read_list(str(tmp_path), "ICE")
    assert [(t[0], t[2]) for t in tests] == [("plain", 1), ("short", 2), ("edited", 8)]    # each name once
    text, root, _ = ud.deck_text(tests[1][1], 3, every_step=True)
    assert root.findtext("Time/maxTime").strip() == "0.0001" and root.findtext("Time/max_Timesteps") == "3"
    assert root.findtext("DataArchiver/outputTimestepInterval") == "1" and root.find("DataArchiver/outputInterval") is None
    text, root, _ = ud.deck_text(tests[2][1], 5, every_step=False)
    assert root.find("Grid/BoundaryConditions/Face/BCType").get("var") == "powerLawProfile"
    assert root.find("DataAnalysis") is None and root.findtext("DataArchiver/outputInterval") == "0.1"
    assert ud.out_of_scope(root, []) is None
    assert ud.out_of_scope(root, ["preProcessCmd=pfs"]) == "needs a preprocessing command"
