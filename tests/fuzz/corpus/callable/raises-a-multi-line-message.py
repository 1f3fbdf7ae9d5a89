# Found by the fuzzer: an exception whose message has line ends and escapes made a row's message of several lines.
def f(case):
    raise RuntimeError('two\nlines\r\x1b[31m \ud800')
