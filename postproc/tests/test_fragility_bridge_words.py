"""The fragility figures name a &bridge IDA's bridge, not the default arch its &arch
group carries (voussoir-sweep writes both: the &arch holds the ring's values)."""
from types import SimpleNamespace

from voussoir_post.plots.fragility_plot import arch_words


def test_bridge_named_not_arch():
    bridge = {"shape": "segmental", "span_m": [10.0, 10.0], "rise_m": [2.5, 2.5], "ring_thickness_m": 0.45,
              "n_voussoirs": 20, "fill_density_kg_m3": 2000.0, "fill_level_m": 3.45}
    arch = {"embrace_deg": 156.0, "n_voussoirs": 13, "r_ext_m": 0.508, "thickness_m": 0.45}
    words = arch_words(SimpleNamespace(config={"arch": arch, "bridge": bridge}, path="ida_bridge.h5"))
    assert words == "bridge of 2 segmental spans of 10, 10 m (rise 2.5, 2.5 m), ring 450 mm of 20 voussoirs, with fill"
    no_fill = dict(bridge, fill_density_kg_m3=0.0)
    words = arch_words(SimpleNamespace(config={"arch": arch, "bridge": no_fill, "vehicle": {"name": "x"}}, path=""))
    assert words == "bridge of 2 segmental spans of 10, 10 m (rise 2.5, 2.5 m), ring 450 mm of 20 voussoirs, " \
                    "a standing vehicle"


def test_arch_unchanged():
    arch = {"embrace_deg": 156.0, "n_voussoirs": 13, "r_ext_m": 0.508, "thickness_m": 0.071}
    words = arch_words(SimpleNamespace(config={"arch": arch}, path="ida.h5"))
    assert words == "156-degree arch of 13 voussoirs (r_ext 0.508 m, t 0.071 m)"
