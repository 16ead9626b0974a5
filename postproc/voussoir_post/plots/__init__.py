"""The figures, one module each (:mod:`.envelope`, :mod:`.sequence`, :mod:`.history`,
:mod:`.compare`, :mod:`.mechanism`, :mod:`.fragility_plot`, :mod:`.fragility_compare`)
over the shared look of :mod:`.drawing`, and the ParaView export (:mod:`.xdmf`). Each
plotting function takes what a reader returned, writes a PNG and returns the numbers it
drew."""
