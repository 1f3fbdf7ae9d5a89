# issue 33 (11): 2**63 gave 'Unable to cast Python instance to C++ type'
{'scene': 'pair', 'pulse': 'sine', 'directivity': 'normal', 'pi2': 1, 'pi3': 0.5, 'eps': 0.5, 'pi5': 0.5, 'pi6': 1, 'solver': 'moreau-jean', 'steps': 2**63}
