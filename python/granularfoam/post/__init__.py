"""Post-processing of the tutorials: measurements and the paper's figures,
each module also a command (`/usr/bin/python3 -m granularfoam.post.<name>`).

    chute           the chute of section 5: figures 2-6, the outflow
    bulbousHead     section 6.2: figure 8, the front and the head
    drum            the square drum of section 7: figures 10, 11, 13, lobes
    drumTension     the drum's lowest grain pressure, step by step
    drumSidewall    the drum's avalanche and core with sidewall friction
    columnCollapse  the monodisperse column collapse: front, deposit
"""
