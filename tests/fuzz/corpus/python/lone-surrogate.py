# issue 33 (11): a lone surrogate gave 'Unable to cast Python instance to C++ type'
{'scene': '\ud800', 'pulse': 'sine', 'directivity': 'normal', 'pi2': 1, 'pi3': 0.5, 'eps': 0.5}
