garbage
more
