 plot.lines{{y = {1, 2}}, width = 1e300}
plot.lines{{x = {-1.7e308, 1.7e308}, y = {1.7e308, 1.7e308}}}
plot.lines{{x = {0, 5e-324}, y = {5e-324, 5e-324}}}